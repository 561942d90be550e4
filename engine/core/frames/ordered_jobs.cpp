#include "frames/ordered_jobs.hpp"

#include <stdexcept>

namespace pathlet {

namespace {
void cancel_quietly(const OrderedJobs::Job& job) {
    try {
        if (job.cancel) job.cancel();
    } catch (...) {  // cancel is clean-up; nothing to report beyond the error that caused it
    }
}
}  // namespace

OrderedJobs::OrderedJobs(int threads, size_t capacity) : capacity_(capacity) {
    if (threads < 1 || capacity < 1) throw std::invalid_argument("OrderedJobs: threads and capacity must be >= 1");
    for (int i = 0; i < threads; ++i) workers_.emplace_back([this] { worker(); });
}

OrderedJobs::~OrderedJobs() { abandon(); }

void OrderedJobs::enqueue(std::unique_lock<std::mutex>&, Job job) {
    queue_.push_back({next_seq_++, std::move(job)});
    ++pending_;
    changed_.notify_all();
}

void OrderedJobs::rethrow_locked(Job* job) {
    std::exception_ptr e = error_;
    if (!e) e = std::make_exception_ptr(std::logic_error("OrderedJobs: submit after abandon"));
    if (job) cancel_quietly(*job);
    std::rethrow_exception(e);
}

void OrderedJobs::submit(Job job) {
    std::unique_lock<std::mutex> lock(mutex_);
    changed_.wait(lock, [&] { return pending_ < capacity_ || error_ || abandoned_; });
    if (error_ || abandoned_) rethrow_locked(&job);
    enqueue(lock, std::move(job));
}

bool OrderedJobs::try_submit(Job& job) {
    std::unique_lock<std::mutex> lock(mutex_);
    if (error_ || abandoned_) rethrow_locked(&job);
    if (pending_ >= capacity_) return false;
    enqueue(lock, std::move(job));
    return true;
}

void OrderedJobs::finish() {
    std::unique_lock<std::mutex> lock(mutex_);
    changed_.wait(lock, [&] { return pending_ == 0; });
    if (error_) std::rethrow_exception(error_);
}

void OrderedJobs::abandon() {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        if (shutdown_) return;
        abandoned_ = true;
        shutdown_ = true;  // workers leave once the queue is empty (its jobs are cancelled in order)
        changed_.notify_all();
    }
    for (auto& t : workers_) t.join();
}

size_t OrderedJobs::pending() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return pending_;
}

size_t OrderedJobs::committed() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return committed_;
}

void OrderedJobs::worker() {
    std::unique_lock<std::mutex> lock(mutex_);
    for (;;) {
        changed_.wait(lock, [&] { return !queue_.empty() || shutdown_; });
        if (queue_.empty()) return;
        Entry e = std::move(queue_.front());
        queue_.pop_front();

        std::exception_ptr failed;
        if (!error_ && !abandoned_) {
            lock.unlock();
            try {
                if (e.job.work) e.job.work();
            } catch (...) {
                failed = std::current_exception();
            }
            lock.lock();
        }
        // Jobs are taken oldest first, so the job whose turn it is is always running or
        // waiting here: this wait ends.
        changed_.wait(lock, [&] { return next_commit_ == e.seq; });
        if (failed && !error_) error_ = failed;
        const bool commit = !error_ && !abandoned_;
        lock.unlock();
        bool committed = false;
        if (commit) {
            try {
                if (e.job.commit) e.job.commit();
                committed = true;
            } catch (...) {
                failed = std::current_exception();
            }
        }
        if (!committed) cancel_quietly(e.job);
        e.job = {};  // its memory goes before the next job may be submitted
        lock.lock();
        if (failed && !error_) error_ = failed;
        ++next_commit_;
        --pending_;
        committed_ += committed;
        changed_.notify_all();
    }
}

}  // namespace pathlet
