// The Python module's one GL context per process: a thread that owns the Runtime (plugins
// and the headless context) and runs every job that touches them, one at a time, in the
// order asked. Any Python thread may ask; the caller waits (with the GIL released, so other
// Python threads go on) and gets the job's result or its exception. Once closed, asking is
// an error: the context is gone for the rest of the process.
#pragma once

#include "runtime.hpp"

#include <condition_variable>
#include <deque>
#include <functional>
#include <future>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <thread>

namespace pathlet::python {

struct ClosedError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

class GlThread {
public:
    // Leaked on purpose: it must outlive interpreter shutdown (pathlet.close() runs at exit).
    static GlThread& get() {
        static GlThread* t = new GlThread;
        return *t;
    }

    // Runs f(runtime) on the GL thread and returns its result; rethrows what it threw.
    template <class F>
    auto call(F&& f) -> decltype(f(std::declval<Runtime&>())) {
        using R = decltype(f(std::declval<Runtime&>()));
        auto task = std::make_shared<std::packaged_task<R()>>([this, fn = std::forward<F>(f)]() mutable {
            if (!rt_) {
                rt_ = std::make_unique<Runtime>();
                rt_->load_plugins({});
            }
            return fn(*rt_);
        });
        std::future<R> result = task->get_future();
        {
            std::lock_guard<std::mutex> lock(mu_);
            if (closed_) throw ClosedError(closed_message());
            if (!thread_.joinable()) thread_ = std::thread([this] { loop(); });
            jobs_.push_back([task] { (*task)(); });
        }
        cv_.notify_one();
        return result.get();
    }

    // Frees the context and the plugins on their thread and ends it. Idempotent.
    void close() {
        {
            std::lock_guard<std::mutex> lock(mu_);
            if (closed_) return;
            closed_ = true;
            jobs_.push_back([this] { rt_.reset(); });
            stop_ = true;
        }
        cv_.notify_one();
        if (thread_.joinable()) thread_.join();
    }
    bool closed() {
        std::lock_guard<std::mutex> lock(mu_);
        return closed_;
    }
    static const char* closed_message() {
        return "pathlet.close() was called: this process's GL context is gone (there is one per process); "
               "start a new Python process to render again";
    }

private:
    GlThread() = default;
    void loop() {
        for (;;) {
            std::function<void()> job;
            {
                std::unique_lock<std::mutex> lock(mu_);
                cv_.wait(lock, [&] { return !jobs_.empty() || stop_; });
                if (jobs_.empty()) return;
                job = std::move(jobs_.front());
                jobs_.pop_front();
            }
            job();
        }
    }

    std::mutex mu_;
    std::condition_variable cv_;
    std::deque<std::function<void()>> jobs_;
    std::thread thread_;
    bool closed_ = false, stop_ = false;
    std::unique_ptr<Runtime> rt_;  // touched only on the GL thread
};

}  // namespace pathlet::python
