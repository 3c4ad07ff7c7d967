// Background jobs: long work (opening data, later surfaces and clustering) runs on its own
// thread with progress and cancel; its result is handed back on the UI thread by poll().
#pragma once

#include <atomic>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace faultline::ui {

// What the work function sees: report progress, check for cancel.
class JobControl {
  public:
    void setProgress(float fraction) { m_progress.store(fraction); } // 0..1; < 0: unknown
    bool cancelled() const { return m_cancel.load(); }

  private:
    friend class Job;
    friend class JobRunner;
    std::atomic<float> m_progress{-1.0f};
    std::atomic<bool> m_cancel{false};
};

class Job {
  public:
    const std::string& title() const { return m_title; }
    float progress() const { return m_control.m_progress.load(); }
    void cancel() { m_control.m_cancel.store(true); }
    bool cancelRequested() const { return m_control.m_cancel.load(); }
    bool finished() const { return m_finished.load(); }
    double startTime() const { return m_startTime; }

  private:
    friend class JobRunner;
    std::string m_title;
    double m_startTime = 0;
    JobControl m_control;
    std::atomic<bool> m_finished{false};
    std::string m_error;            // set by the worker when work threw
    std::function<void()> m_finish; // runs on the UI thread (not when cancelled)
    std::function<void(const std::string&)> m_fail;
    std::thread m_thread;
};

class JobRunner {
  public:
    using Work = std::function<std::function<void()>(JobControl&)>;
    using Fail = std::function<void(const std::string& error)>;

    JobRunner() = default;
    ~JobRunner(); // asks every job to cancel and joins it
    JobRunner(const JobRunner&) = delete;
    JobRunner& operator=(const JobRunner&) = delete;

    // Runs `work` on a new thread. Its return value (a closure) runs on the UI thread in poll()
    // unless the job was cancelled; when `work` throws, `fail` runs there with the message.
    std::shared_ptr<Job> start(std::string title, Work work, Fail fail, double now);

    // UI thread, once per frame: finishes jobs that are done. Returns true when any finished.
    bool poll();
    // Jobs still running (for the status bar), oldest first.
    std::vector<std::shared_ptr<Job>> running() const;
    bool busy() const;
    // Blocks until every running job's work is done; its result is handed over by the next
    // poll() (tests, shutdown).
    void waitAll();
    // Called by a worker when it ends (e.g. to wake an idle event loop).
    void setWakeUp(std::function<void()> wake) { m_wake = std::move(wake); }

  private:
    mutable std::mutex m_mutex;
    std::vector<std::shared_ptr<Job>> m_jobs;
    std::function<void()> m_wake;
};

} // namespace faultline::ui
