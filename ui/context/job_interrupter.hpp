// JobInterrupter: a surface build's stages (plan, field, mesh) as one job's progress, and the
// job's cancel as the build's interrupter.
#pragma once

#include "core/surface/interrupter.hpp"
#include "ui/context/jobs.hpp"

#include <algorithm>
#include <string>

namespace faultline::ui {

// The build's stages as one progress fraction; cancel from the job.
class JobInterrupter : public core::Interrupter {
  public:
    explicit JobInterrupter(JobControl& control) : m_control(control) {}
    void start(const char* stage) override {
        const std::string s = stage;
        m_base = s == "plan" ? 0.0f : s == "field" ? 0.1f : 0.75f;
        m_span = s == "plan" ? 0.1f : s == "field" ? 0.65f : 0.25f;
        m_control.setProgress(m_base);
    }
    bool wasInterrupted(int percent) override {
        if (percent >= 0)
            m_control.setProgress(m_base + m_span * std::min(percent, 100) / 100.0f);
        return m_control.cancelled();
    }

  private:
    JobControl& m_control;
    float m_base = 0.0f, m_span = 0.1f;
};

} // namespace faultline::ui
