// Figures of a session: one view (its frame binding, colouring, camera, boxes, the session's
// visibility) rendered offscreen to a PNG. Behind the journal's "render" op and `faultline render`.
#pragma once

#include "core/session/session.hpp"

#include <optional>
#include <string>

namespace faultline::ui {

struct FigureRequest {
    std::string view = "main";
    std::string path;
    int width = 1280;
    int height = 720;
    bool transparent = false;
    std::optional<std::size_t> frame; // overrides the view's frame binding
};

// Throws core::CommandError with the reason (no such view, no data, no display, write failed).
void renderSessionFigure(core::Session& session, const FigureRequest& request);

// Adds {"op":"render","view":..,"path":..,"size":[w,h],"transparent":..,"frame":..} to a session.
void registerRenderOp(core::Session& session);

} // namespace faultline::ui
