#include "ui/render/renderer.hpp"

#include "ui/render/gl_renderer.hpp"
#include "ui/render/mock_renderer.hpp"

#include <cassert>

namespace faultline::ui {

std::unique_ptr<Renderer> createRenderer(RendererBackend backend) {
    if (backend == RendererBackend::Mock)
        return std::make_unique<MockRenderer>();
    return std::make_unique<GlRenderer>();
}

void compactRows(std::size_t count, std::span<const std::uint8_t> mask,
                 std::vector<std::uint32_t>& visible, std::vector<std::uint32_t>* hidden) {
    assert(mask.empty() || mask.size() == count);
    visible.clear();
    if (hidden)
        hidden->clear();
    if (mask.empty()) {
        visible.resize(count);
        for (std::size_t i = 0; i < count; ++i)
            visible[i] = static_cast<std::uint32_t>(i);
        return;
    }
    for (std::size_t i = 0; i < count; ++i) {
        if (mask[i])
            visible.push_back(static_cast<std::uint32_t>(i));
        else if (hidden)
            hidden->push_back(static_cast<std::uint32_t>(i));
    }
}

} // namespace faultline::ui
