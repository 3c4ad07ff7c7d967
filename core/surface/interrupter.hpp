// Interrupter: progress and cancel for long surface jobs (the UI runs them in the background).
// Modelled on OpenVDB's interrupter contract; wasInterrupted() may be called from worker threads.
#pragma once

#include <stdexcept>
#include <string>

namespace faultline::core {

class Interrupter {
  public:
    virtual ~Interrupter() = default;
    // A new stage begins ("plan", "field", "mesh", ...).
    virtual void start(const char* stage) { (void)stage; }
    // Returns true to cancel. percent is the stage's progress in [0, 100], or -1 when unknown.
    // Must be thread-safe: it is called from worker threads.
    virtual bool wasInterrupted(int percent = -1) {
        (void)percent;
        return false;
    }
    virtual void end() {}
};

// Thrown when an Interrupter asked to stop; nothing half-built escapes.
class SurfaceCancelled : public std::runtime_error {
  public:
    SurfaceCancelled() : std::runtime_error("surface build cancelled") {}
};

// Thrown for a request that is refused before any work starts (empty set, memory budget, ...).
class SurfaceRequestError : public std::runtime_error {
  public:
    explicit SurfaceRequestError(const std::string& message) : std::runtime_error(message) {}
};

} // namespace faultline::core
