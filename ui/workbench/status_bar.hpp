// The status bar along the window's bottom: background jobs with their progress and Cancel,
// the frame being loaded, the last message (an error stays, information fades after 10 s; the
// whole text in a tooltip), and on the right the frame, timestep and spheres visible.
#pragma once

#include <string>

namespace faultline::ui {

class PanelContext;

class StatusBar {
  public:
    void info(std::string text, double now) { set(std::move(text), false, now); }
    void error(std::string text, double now) { set(std::move(text), true, now); }
    const std::string& message() const { return m_message; }
    bool messageIsError() const { return m_isError; }

    // A window of `height` pixels at the bottom of the display.
    void draw(PanelContext& ctx, float height);

  private:
    void set(std::string text, bool isError, double now) {
        m_message = std::move(text);
        m_isError = isError;
        m_time = now;
    }
    std::string m_message;
    bool m_isError = false;
    double m_time = 0.0;
};

} // namespace faultline::ui
