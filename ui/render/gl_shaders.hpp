// GLSL sources of the renderer's passes (GLSL 4.10 core): sphere impostors, context points,
// meshes, thick box edges, screen-space contact darkening, down-sampling and the 2-D overlay.
#pragma once

#include <string>

namespace faultline::ui::gl::shaders {

// Ray-cast sphere impostors: one triangle per sphere pulled from buffer textures by row.
std::string sphereVertex(bool perspective);
std::string sphereFragment(bool perspective);
// Hidden spheres as round points of a fixed size and colour.
std::string pointVertex();
std::string pointFragment();
// Triangle meshes with per-vertex colour and normals, one opacity.
std::string meshVertex();
std::string meshFragment();
// Screen-space thick lines pulled from a buffer texture of segments.
std::string lineVertex();
std::string lineFragment();
// A full-screen triangle; screen-space occlusion from the depth buffer (creases between
// spheres), and the composite that blurs it and darkens the colour with it.
std::string fullscreenVertex();
std::string ambientOcclusionFragment();
std::string compositeFragment();
std::string downsampleFragment();
// 2-D quads in pixels: solid, text (alpha atlas), or the colour map along v.
std::string overlayVertex();
std::string overlayFragment();

} // namespace faultline::ui::gl::shaders
