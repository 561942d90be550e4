// The render's writer pool (frames/ordered_jobs.hpp): commits in submission order, a bounded
// number of jobs alive (back-pressure), the first error stops the rest, abandon cancels.
#include "frames/ordered_jobs.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <random>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace pathlet {
namespace {

// Counts the payloads alive (what a queued frame's pixels would be) and the most at once.
struct Census {
    std::atomic<int> alive{0}, most{0};
    void born() {
        const int n = ++alive;
        int m = most.load();
        while (n > m && !most.compare_exchange_weak(m, n)) {}
    }
};
struct Payload {
    Census& c;
    explicit Payload(Census& census) : c(census) { c.born(); }
    ~Payload() { --c.alive; }
};

// Holds workers inside their work until opened.
class Gate {
public:
    void open() {
        std::lock_guard<std::mutex> l(m_);
        open_ = true;
        cv_.notify_all();
    }
    void wait() {
        std::unique_lock<std::mutex> l(m_);
        cv_.wait(l, [&] { return open_; });
    }

private:
    std::mutex m_;
    std::condition_variable cv_;
    bool open_ = false;
};

TEST(OrderedJobs, CommitsInSubmissionOrderWhateverTheWorkTakes) {
    OrderedJobs jobs(3, 5);
    std::vector<int> order;  // commits are one at a time: no lock needed
    std::mt19937 rng(7);
    for (int i = 0; i < 120; ++i) {
        const int us = int(rng() % 2000);  // later jobs often finish their work first
        jobs.submit({[us] { std::this_thread::sleep_for(std::chrono::microseconds(us)); },
                     [&order, i] { order.push_back(i); }, {}});
    }
    jobs.finish();
    ASSERT_EQ(order.size(), 120u);
    for (int i = 0; i < 120; ++i) ASSERT_EQ(order[size_t(i)], i);
    EXPECT_EQ(jobs.committed(), 120u);
    EXPECT_EQ(jobs.pending(), 0u);
}

TEST(OrderedJobs, AtMostCapacityJobsAreAliveWhileTheProducerRunsAhead) {
    // A producer far faster than the workers (the render thread against PNG encoders): the
    // jobs alive never exceed the capacity, plus the one being handed over.
    for (const size_t capacity : {1u, 3u, 6u}) {
        Census census;
        {
            OrderedJobs jobs(2, capacity);
            for (int i = 0; i < 60; ++i) {
                auto p = std::make_shared<Payload>(census);
                jobs.submit({[p] { std::this_thread::sleep_for(std::chrono::microseconds(300)); }, [p] {}, [p] {}});
                EXPECT_LE(jobs.pending(), capacity);
            }
            jobs.finish();
        }
        EXPECT_EQ(census.alive.load(), 0) << "every payload released";
        EXPECT_LE(census.most.load(), int(capacity) + 1) << "capacity " << capacity;
        EXPECT_GE(census.most.load(), int(capacity)) << "the queue fills up to its capacity " << capacity;
    }
}

TEST(OrderedJobs, AFullQueueRefusesUntilAJobIsCommitted) {
    Gate gate;
    OrderedJobs jobs(2, 3);
    std::atomic<int> committed{0};
    for (int i = 0; i < 3; ++i) jobs.submit({[&] { gate.wait(); }, [&] { ++committed; }, {}});
    OrderedJobs::Job extra{{}, [&] { ++committed; }, {}};
    EXPECT_EQ(jobs.pending(), 3u);
    EXPECT_FALSE(jobs.try_submit(extra)) << "full: the caller must wait";
    gate.open();
    jobs.finish();
    EXPECT_TRUE(jobs.try_submit(extra));
    jobs.finish();
    EXPECT_EQ(committed.load(), 4);
}

TEST(OrderedJobs, TheFirstErrorCancelsLaterJobsAndReachesTheSubmitter) {
    OrderedJobs jobs(3, 4);
    std::vector<int> committed, cancelled;
    std::mutex m;
    auto job = [&](int i) {
        return OrderedJobs::Job{[i] {
                                    if (i == 5) throw std::runtime_error("frame 5: disk full");
                                },
                                [&, i] { committed.push_back(i); },
                                [&, i] {
                                    std::lock_guard<std::mutex> l(m);
                                    cancelled.push_back(i);
                                }};
    };
    std::string error;
    try {
        for (int i = 0; i < 40; ++i) jobs.submit(job(i));
        jobs.finish();
    } catch (const std::runtime_error& e) {
        error = e.what();
    }
    EXPECT_EQ(error, "frame 5: disk full");
    EXPECT_EQ(committed, (std::vector<int>{0, 1, 2, 3, 4})) << "what came before the failure is kept, in order";
    jobs.abandon();
    for (int c : cancelled) EXPECT_GE(c, 5) << "only the failed job and later ones are cancelled";
    EXPECT_NE(std::find(cancelled.begin(), cancelled.end(), 5), cancelled.end()) << "the failed job cleans up too";
    // After the error every submit fails at once, and its job is cancelled (its temp removed).
    bool cleaned = false;
    EXPECT_THROW(jobs.submit({{}, {}, [&] { cleaned = true; }}), std::exception);
    EXPECT_TRUE(cleaned);
}

TEST(OrderedJobs, ACommitThatThrowsStopsTheRest) {
    OrderedJobs jobs(2, 8);
    std::vector<int> committed;
    for (int i = 0; i < 6; ++i)
        jobs.submit({{}, [&committed, i] {
                         if (i == 2) throw std::runtime_error("video.mp4: ffmpeg stopped accepting frames");
                         committed.push_back(i);
                     },
                     {}});
    EXPECT_THROW(jobs.finish(), std::runtime_error);
    EXPECT_EQ(committed, (std::vector<int>{0, 1}));
}

TEST(OrderedJobs, AbandonCancelsEverythingNotCommitted) {
    Gate gate;
    std::atomic<int> committed{0}, cancelled{0}, worked{0};
    {
        OrderedJobs jobs(1, 10);
        for (int i = 0; i < 10; ++i)
            jobs.submit({[&] {
                             ++worked;
                             gate.wait();
                         },
                         [&] { ++committed; }, [&] { ++cancelled; }});
        while (worked.load() == 0) std::this_thread::yield();  // the first job is running
        std::thread opener([&] {
            std::this_thread::sleep_for(std::chrono::milliseconds(20));
            gate.open();
        });
        jobs.abandon();  // waits for the running job; the nine queued ones are never worked on
        opener.join();
    }
    EXPECT_EQ(committed.load(), 0);
    EXPECT_EQ(cancelled.load(), 10);
    EXPECT_EQ(worked.load(), 1);
}

}  // namespace
}  // namespace pathlet
