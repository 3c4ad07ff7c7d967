#include "ui/context/jobs.hpp"

#include <chrono>
#include <exception>

namespace faultline::ui {

JobRunner::~JobRunner() {
    std::vector<std::shared_ptr<Job>> jobs;
    {
        std::lock_guard lock(m_mutex);
        jobs = m_jobs;
    }
    for (auto& j : jobs)
        j->cancel();
    for (auto& j : jobs)
        if (j->m_thread.joinable())
            j->m_thread.join();
}

std::shared_ptr<Job> JobRunner::start(std::string title, Work work, Fail fail, double now) {
    auto job = std::make_shared<Job>();
    job->m_title = std::move(title);
    job->m_startTime = now;
    job->m_fail = std::move(fail);
    {
        std::lock_guard lock(m_mutex);
        m_jobs.push_back(job);
    }
    Job* raw = job.get();
    job->m_thread = std::thread([this, raw, work = std::move(work)] {
        try {
            raw->m_finish = work(raw->m_control);
        } catch (const std::exception& e) {
            raw->m_error = e.what();
            if (raw->m_error.empty())
                raw->m_error = "failed";
        } catch (...) {
            raw->m_error = "failed with an unknown error";
        }
        raw->m_finished.store(true);
        if (m_wake)
            m_wake();
    });
    return job;
}

bool JobRunner::poll() {
    std::vector<std::shared_ptr<Job>> done;
    {
        std::lock_guard lock(m_mutex);
        for (auto it = m_jobs.begin(); it != m_jobs.end();) {
            if ((*it)->finished()) {
                done.push_back(*it);
                it = m_jobs.erase(it);
            } else {
                ++it;
            }
        }
    }
    for (auto& job : done) {
        job->m_thread.join();
        if (job->cancelRequested())
            continue;
        if (!job->m_error.empty()) {
            if (job->m_fail)
                job->m_fail(job->m_error);
        } else if (job->m_finish) {
            job->m_finish();
        }
    }
    return !done.empty();
}

std::vector<std::shared_ptr<Job>> JobRunner::running() const {
    std::lock_guard lock(m_mutex);
    return m_jobs;
}

bool JobRunner::busy() const {
    std::lock_guard lock(m_mutex);
    return !m_jobs.empty();
}

void JobRunner::waitAll() {
    for (auto& j : running())
        while (!j->finished())
            std::this_thread::sleep_for(std::chrono::milliseconds(1));
}

} // namespace faultline::ui
