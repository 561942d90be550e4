// A small pool of worker threads for a render's output work (encoding images, feeding a
// video) with three promises:
//  * order: each job's `commit` runs after every earlier job's, one at a time, so files are
//    renamed into place (and frames reach the video) in frame order;
//  * bounded memory: at most `capacity` jobs are pending (submitted, not yet committed or
//    cancelled); submit() blocks the caller until one is done (back-pressure);
//  * errors stop the rest: the first exception of a work or commit is kept, every later job
//    is cancelled instead of committed, and submit()/finish() rethrow it.
#pragma once

#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

namespace pathlet {

class OrderedJobs {
public:
    struct Job {
        std::function<void()> work;    // on a worker, in parallel with other jobs' work
        std::function<void()> commit;  // on a worker, in submission order, one at a time
        std::function<void()> cancel;  // instead of commit (after an error, or abandon()); must not throw
    };

    // threads >= 1, capacity >= 1.
    OrderedJobs(int threads, size_t capacity);
    ~OrderedJobs();  // abandon()
    OrderedJobs(const OrderedJobs&) = delete;
    OrderedJobs& operator=(const OrderedJobs&) = delete;

    // Blocks while `capacity` jobs are pending. After a job failed: cancels `job` and rethrows.
    void submit(Job job);
    // Like submit without blocking: false (job untouched) when `capacity` jobs are pending.
    bool try_submit(Job& job);
    // Waits until every submitted job is committed or cancelled; rethrows the first error.
    void finish();
    // Cancels every job not yet committed (their work is skipped where it has not started)
    // and waits for the workers. Never throws; the pool takes no more jobs.
    void abandon();

    size_t pending() const;
    size_t committed() const;
    size_t capacity() const { return capacity_; }
    int threads() const { return int(workers_.size()); }

private:
    struct Entry {
        uint64_t seq = 0;
        Job job;
    };
    void worker();
    void enqueue(std::unique_lock<std::mutex>& lock, Job job);
    void rethrow_locked(Job* job);

    const size_t capacity_;
    mutable std::mutex mutex_;
    std::condition_variable changed_;
    std::deque<Entry> queue_;  // waiting for a worker, oldest first
    uint64_t next_seq_ = 0, next_commit_ = 0;
    size_t pending_ = 0, committed_ = 0;
    std::exception_ptr error_;
    bool abandoned_ = false, shutdown_ = false;
    std::vector<std::thread> workers_;
};

}  // namespace pathlet
