// Index of this file:
// [SECTION] Shared GLSL: header, colour maps, shading
// [SECTION] Sphere impostors
// [SECTION] Points, meshes and lines
// [SECTION] Screen-space passes: ambient occlusion and the rest

#include "ui/render/gl_shaders.hpp"

namespace faultline::ui::gl::shaders {

namespace {

//-----------------------------------------------------------------------------
// [SECTION] Shared GLSL: header, colour maps, shading
//-----------------------------------------------------------------------------

const char* kHeader = "#version 410 core\n";

// Colour map lookup shared by spheres and the legend bar. Continuous maps sample a table
// linearly; band maps pick palette entry floor(t * bands) mod palette size.
const char* kColorMap = R"(
uniform sampler2D uColorMap;
uniform int uBandCount;
vec3 mapColor(float t) {
    t = clamp(t, 0.0, 1.0);
    int width = textureSize(uColorMap, 0).x;
    if (uBandCount > 0) {
        int band = min(int(floor(t * float(uBandCount))), uBandCount - 1);
        return texelFetch(uColorMap, ivec2(band % width, 0), 0).rgb;
    }
    float w = float(width);
    return textureLod(uColorMap, vec2((t * (w - 1.0) + 0.5) / w, 0.5), 0.0).rgb;
}
)";

// Lighting shared by spheres and meshes, in view space. Gamma 2 (square / square root) stands in
// for sRGB: close enough for shading and cheap on a CPU rasteriser.
const char* kShading = R"(
uniform float uSpecular;
vec3 shade(vec3 srgb, vec3 n, vec3 V) {
    vec3 base = srgb * srgb;
    const vec3 key = vec3(-0.4319, 0.5759, 0.6943);  // upper left, towards the viewer
    const vec3 fill = vec3(0.6097, -0.2540, 0.7508); // lower right, weaker
    float kd = max(dot(n, key), 0.0);
    float fd = max(dot(n, fill), 0.0);
    float sky = 0.5 + 0.5 * n.y;
    vec3 h = normalize(key + V);
    float s = max(dot(n, h), 0.0);
    s *= s; s *= s; s *= s; s *= s; s *= s; // ^32
    // Grazing normals face neighbouring spheres: darken them a little (cheap occlusion).
    float facing = max(dot(n, V), 0.0);
    float occlusion = 0.62 + 0.38 * sqrt(facing);
    vec3 lit = base * ((0.16 + 0.12 * sky) + 0.74 * kd + 0.20 * fd) * occlusion;
    return sqrt(lit) + vec3(uSpecular * s);
}
)";

} // namespace

//-----------------------------------------------------------------------------
// [SECTION] Sphere impostors
//-----------------------------------------------------------------------------

std::string sphereVertex(bool perspective) {
    return std::string(kHeader) +
           (perspective ? "#define PERSPECTIVE 1\n" : "#define PERSPECTIVE 0\n") + kColorMap + R"(
uniform samplerBuffer uSpheres;  // x y z radius per row
uniform samplerBuffer uValues;   // colour variable per row
uniform usamplerBuffer uRows;    // rows to draw, one triangle each
uniform mat4 uView;
uniform mat4 uProj;
uniform float uNearZ;            // view z of the near plane (< 0 in perspective)
uniform int uColorMode;          // 0: uColor, 1: colour map of the value
uniform vec3 uColor;
uniform vec3 uNanColor;
uniform vec2 uRange;             // low, 1 / (high - low)
flat out vec4 vSphere;           // view-space centre, radius
flat out uint vColor;            // packed sRGB
out vec3 vPos;                   // view-space point on the billboard
// One equilateral triangle around the unit circle: three vertices per sphere, the fewest, as
// vertex work bounds the cost of drawing every sphere on a CPU rasteriser.
const vec2 kCorners[3] = vec2[3](vec2(0.0, 2.0), vec2(-1.7320508, -1.0), vec2(1.7320508, -1.0));
void skip() {
    vPos = vec3(0.0);
    gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
}
#if PERSPECTIVE
// Screen extent along one axis (scale s: uProj[0][0] or [1][1]) of the part of the sphere beyond
// the near plane. In the plane through the eye, that axis and the view direction the sphere is a
// circle (a, z, r); the extremes of a / -z over the circle cut by the near line are the tangent
// points from the eye that lie beyond the near plane and the two points where the near line
// crosses the circle.
vec2 clippedExtent(float a, float z, float r, float s) {
    vec2 e = vec2(1e30, -1e30);
    float l2 = a * a + z * z;
    float t2 = l2 - r * r;
    if (t2 > 0.0) { // the eye is outside the circle: two tangent points
        float t = sqrt(t2);
        for (int i = 0; i < 2; ++i) {
            float side = i == 0 ? r : -r;
            vec2 p = (t * vec2(a, z) + side * vec2(-z, a)) * (t / l2);
            if (p.y <= uNearZ) {
                float x = s * p.x / -p.y;
                e = vec2(min(e.x, x), max(e.y, x));
            }
        }
    }
    float k2 = r * r - (uNearZ - z) * (uNearZ - z);
    if (k2 > 0.0) { // the near plane cuts the circle
        float k = sqrt(k2);
        e = vec2(min(e.x, s * (a - k) / -uNearZ), max(e.y, s * (a + k) / -uNearZ));
    }
    return e;
}
#endif
void main() {
    int q = gl_VertexID / 3;
    int k = gl_VertexID - 3 * q;
    int row = int(texelFetch(uRows, q).r);
    vec4 s = texelFetch(uSpheres, row);
    vec3 c = (uView * vec4(s.xyz, 1.0)).xyz;
    float r = s.w;
    vec3 color = uColor;
    if (uColorMode == 1) {
        float v = texelFetch(uValues, row).r;
        color = isnan(v) ? uNanColor : mapColor((v - uRange.x) * uRange.y);
    }
    vColor = packUnorm4x8(vec4(color, 1.0));
    vSphere = vec4(c, r);
    if (r <= 0.0 || c.z - r >= uNearZ) { // wholly in front of the near plane (or behind the eye)
        skip();
        return;
    }
#if PERSPECTIVE
    float d2 = dot(c, c);
    float t2 = d2 - r * r;
    if (t2 > 0.0) {
        float d = sqrt(d2);
        vec3 f = c / d;
        // The plane touching the sphere's near tip, cut by the cone of rays tangent to the
        // sphere: every ray that meets the sphere crosses this disc first (so depth only grows
        // from it). Used when the whole triangle around it lies beyond the near plane.
        float h = r * (d - r) * inversesqrt(t2);
        vec3 centre = f * (d - r);
        if (centre.z + 2.0 * h * sqrt(max(1.0 - f.z * f.z, 0.0)) < uNearZ * 1.001) {
            vec3 u = abs(f.y) < 0.999 ? normalize(vec3(-f.z, 0.0, f.x)) : vec3(1.0, 0.0, 0.0);
            vec3 w = cross(f, u);
            vec2 o = kCorners[k] * h;
            vPos = centre + u * o.x + w * o.y;
            gl_Position = uProj * vec4(vPos, 1.0);
            return;
        }
    }
    // Near the eye, or the eye inside: a triangle in the near plane around the screen rectangle
    // of the sphere's part beyond it (the fragment shader draws the cut face there).
    vec2 ex = clippedExtent(c.x, c.z, r, uProj[0][0]);
    vec2 ey = clippedExtent(c.y, c.z, r, uProj[1][1]);
    vec2 lo = max(vec2(ex.x, ey.x), vec2(-1.0));
    vec2 hi = min(vec2(ex.y, ey.y), vec2(1.0));
    if (lo.x > hi.x || lo.y > hi.y) {
        skip();
        return;
    }
    vec2 span = 2.05 * (hi - lo) + 1e-3;
    vec2 ndc = k == 0 ? lo : (k == 1 ? vec2(lo.x + span.x, lo.y) : vec2(lo.x, lo.y + span.y));
    float n = -uNearZ;
    vPos = vec3(ndc.x * n / uProj[0][0], ndc.y * n / uProj[1][1], uNearZ);
    gl_Position = vec4(ndc * n, -n, n); // exactly on the near plane: depth 0
#else
    // Facing the viewer at the sphere's front, or at the near plane when that cuts the sphere.
    vec3 centre = vec3(c.xy, min(c.z + r, uNearZ));
    vPos = centre + vec3(kCorners[k] * r, 0.0);
    gl_Position = uProj * vec4(vPos, 1.0);
    gl_Position.z = max(gl_Position.z, -gl_Position.w);
#endif
}
)";
}

std::string sphereFragment(bool perspective) {
    return std::string(kHeader) + R"(
#ifdef GL_ARB_conservative_depth
#extension GL_ARB_conservative_depth : enable
layout(depth_greater) out float gl_FragDepth;
#endif
)" + (perspective ? "#define PERSPECTIVE 1\n" : "#define PERSPECTIVE 0\n") +
           kShading + R"(
uniform mat4 uProj;
uniform float uNearZ;
flat in vec4 vSphere;
flat in uint vColor;
in vec3 vPos;
layout(location = 0) out vec4 oColor;
// Where the near plane cuts a sphere, the section shows as a flat disc, a little darker than
// the sphere, so a cut reads as a cut and not as a sphere surface.
const float kCutShade = 0.72;
void main() {
    vec3 C = vSphere.xyz;
    float r = vSphere.w;
#if PERSPECTIVE
    // Ray t vPos from the eye: |t vPos - C| = r. The near plane is at t = uNearZ / vPos.z.
    float a = dot(vPos, vPos);
    float b = dot(vPos, C);
    float disc = b * b - a * (dot(C, C) - r * r);
    if (disc < 0.0)
        discard;
    float root = sqrt(disc);
    float tNear = uNearZ / vPos.z;
    float t = (b - root) / a;
    bool cut = t < tNear;
    if (cut && (b + root) / a < tNear)
        discard; // the ray leaves the sphere before the near plane
    vec3 p = vPos * (cut ? tNear : t);
    vec3 V = -normalize(p);
#else
    vec2 dxy = vPos.xy - C.xy;
    float q = r * r - dot(dxy, dxy);
    if (q < 0.0)
        discard;
    float front = C.z + sqrt(q);
    bool cut = front > uNearZ;
    if (cut && C.z - sqrt(q) > uNearZ)
        discard;
    vec3 p = vec3(vPos.xy, cut ? uNearZ : front);
    vec3 V = vec3(0.0, 0.0, 1.0);
#endif
    vec3 base = unpackUnorm4x8(vColor).rgb;
    if (cut) {
        gl_FragDepth = 0.0;
        oColor = vec4(base * kCutShade, 1.0);
        return;
    }
    vec3 n = (p - C) / r;
    float clipZ = uProj[2][2] * p.z + uProj[3][2];
    float clipW = uProj[2][3] * p.z + uProj[3][3];
    gl_FragDepth = 0.5 * (clipZ / clipW) + 0.5;
    oColor = vec4(shade(base, n, V), 1.0);
}
)";
}

//-----------------------------------------------------------------------------
// [SECTION] Points, meshes and lines
//-----------------------------------------------------------------------------

std::string pointVertex() {
    return std::string(kHeader) + R"(
uniform samplerBuffer uSpheres;
uniform usamplerBuffer uRows;
uniform mat4 uView;
uniform mat4 uProj;
uniform float uPointSize;
void main() {
    vec4 s = texelFetch(uSpheres, int(texelFetch(uRows, gl_VertexID).r));
    gl_Position = uProj * (uView * vec4(s.xyz, 1.0));
    gl_PointSize = uPointSize;
}
)";
}

std::string pointFragment() {
    return std::string(kHeader) + R"(
uniform vec4 uColor; // straight alpha
layout(location = 0) out vec4 oColor;
void main() {
    vec2 d = gl_PointCoord - vec2(0.5);
    if (dot(d, d) > 0.25)
        discard;
    oColor = uColor;
}
)";
}

std::string meshVertex() {
    return std::string(kHeader) + R"(
layout(location = 0) in vec3 aPos;
layout(location = 1) in vec3 aNormal; // zero: flat shading
layout(location = 2) in vec4 aColor;  // sRGB, opacity
uniform mat4 uView;
uniform mat4 uProj;
out vec3 vPos;
out vec3 vNormal;
out vec4 vColor;
void main() {
    vec4 p = uView * vec4(aPos, 1.0);
    vPos = p.xyz;
    vNormal = mat3(uView) * aNormal;
    vColor = aColor;
    gl_Position = uProj * p;
}
)";
}

std::string meshFragment() {
    return std::string(kHeader) + kShading + R"(
uniform int uPerspective;
in vec3 vPos;
in vec3 vNormal;
in vec4 vColor;
layout(location = 0) out vec4 oColor;
void main() {
    vec3 V = uPerspective == 1 ? -normalize(vPos) : vec3(0.0, 0.0, 1.0);
    vec3 n = dot(vNormal, vNormal) > 1e-12 ? normalize(vNormal)
                                           : normalize(cross(dFdx(vPos), dFdy(vPos)));
    if (dot(n, V) < 0.0)
        n = -n; // two-sided: surfaces are seen from both sides
    oColor = vec4(shade(vColor.rgb, n, V), vColor.a);
}
)";
}

std::string lineVertex() {
    return std::string(kHeader) + R"(
uniform samplerBuffer uSegments; // per segment: end a, end b, rgba
uniform mat4 uView;
uniform mat4 uProj;
uniform vec2 uViewport;
uniform float uWidth;            // pixels
uniform float uNearZ;            // view z of the near plane; > 0 disables clipping (ortho)
uniform float uAlpha;            // multiplies each segment's alpha
flat out vec4 vColor;
const int kEnd[6] = int[6](0, 0, 1, 1, 0, 1);
const float kSide[6] = float[6](-1.0, 1.0, -1.0, -1.0, 1.0, 1.0);
void main() {
    int s = gl_VertexID / 6;
    int k = gl_VertexID - 6 * s;
    vec3 a = (uView * vec4(texelFetch(uSegments, 3 * s).xyz, 1.0)).xyz;
    vec3 b = (uView * vec4(texelFetch(uSegments, 3 * s + 1).xyz, 1.0)).xyz;
    vec4 color = texelFetch(uSegments, 3 * s + 2);
    vColor = vec4(color.rgb, color.a * uAlpha);
    if (uNearZ <= 0.0) {
        if (a.z > uNearZ && b.z > uNearZ) {
            gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
            return;
        }
        if (a.z > uNearZ) a = mix(b, a, (uNearZ - b.z) / (a.z - b.z));
        if (b.z > uNearZ) b = mix(a, b, (uNearZ - a.z) / (b.z - a.z));
    }
    vec4 ca = uProj * vec4(a, 1.0);
    vec4 cb = uProj * vec4(b, 1.0);
    vec2 half_ = 0.5 * uViewport;
    vec2 sa = ca.xy / ca.w * half_;
    vec2 sb = cb.xy / cb.w * half_;
    vec2 dir = sb - sa;
    float len = length(dir);
    dir = len > 1e-6 ? dir / len : vec2(1.0, 0.0);
    vec2 nrm = vec2(-dir.y, dir.x);
    bool atB = kEnd[k] == 1;
    vec4 c = atB ? cb : ca;
    // Square caps (extend by half the width) so box corners close.
    vec2 offset = (nrm * kSide[k] + dir * (atB ? 1.0 : -1.0)) * (0.5 * uWidth);
    c.xy += offset / half_ * c.w;
    gl_Position = c;
}
)";
}

std::string lineFragment() {
    return std::string(kHeader) + R"(
flat in vec4 vColor;
layout(location = 0) out vec4 oColor;
void main() { oColor = vColor; }
)";
}

//-----------------------------------------------------------------------------
// [SECTION] Screen-space passes: ambient occlusion and the rest
//-----------------------------------------------------------------------------

std::string fullscreenVertex() {
    return std::string(kHeader) + R"(
void main() {
    vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);
    gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}
)";
}

namespace {
const char* kViewDepth = R"(
uniform sampler2D uDepth;
uniform vec2 uNearFar;
uniform int uPerspective;
float viewDepth(float d) {
    float n = uNearFar.x, f = uNearFar.y;
    return uPerspective == 1 ? n * f / (f - d * (f - n)) : n + d * (f - n);
}
)";
} // namespace

std::string ambientOcclusionFragment() {
    return std::string(kHeader) + kViewDepth + R"(
// Golden-angle spiral, radius sqrt((i + 0.5) / 16).
const vec2 kSpiral[16] = vec2[16](
    vec2(0.1768, 0.0000), vec2(-0.2258, 0.2068), vec2(0.0346, -0.3938), vec2(0.2846, 0.3712),
    vec2(-0.5222, -0.0924), vec2(0.4947, -0.3147), vec2(-0.1655, 0.6155), vec2(-0.3156, -0.6076),
    vec2(0.6846, 0.2500), vec2(-0.7123, 0.2940), vec2(0.3434, -0.7337), vec2(0.2537, 0.8089),
    vec2(-0.7647, -0.4432), vec2(0.8971, -0.1972), vec2(-0.5475, 0.7788), vec2(-0.1265, -0.9761));
uniform float uWorldRadius;   // a typical sphere radius: the scale of a crease
uniform float uPixelsPerUnit; // at unit depth (perspective) or everywhere (orthographic)
layout(location = 0) out vec4 oOcclusion; // in red: 0 open, 1 fully occluded
// Drawn at half the scene's resolution (a quarter of the work): texel p stands for scene
// pixel 2p; the taps reach into the full-resolution depth.
void main() {
    ivec2 px = ivec2(gl_FragCoord.xy) * 2;
    float d = texelFetch(uDepth, px, 0).r;
    if (d >= 1.0) {
        oOcclusion = vec4(0.0);
        return;
    }
    ivec2 size = textureSize(uDepth, 0);
    float z = viewDepth(d);
    float radiusPx = 1.2 * uWorldRadius * uPixelsPerUnit / (uPerspective == 1 ? z : 1.0);
    radiusPx = clamp(radiusPx, 2.0, 40.0);
    // Sixteen taps on a golden-angle spiral, turned per pixel (interleaved gradient noise) so
    // big kernels give fine grain, which the composite blurs away, not ghost copies of edges.
    float turn = 6.2831853 * fract(52.9829189 * fract(dot(gl_FragCoord.xy, vec2(0.06711056, 0.00583715))));
    mat2 spin = mat2(cos(turn), sin(turn), -sin(turn), cos(turn)) * radiusPx;
    float occlusion = 0.0;
    for (int i = 0; i < 16; ++i) {
        ivec2 q = clamp(px + ivec2(round(spin * kSpiral[i])), ivec2(0), size - 1);
        float dz = z - viewDepth(texelFetch(uDepth, q, 0).r); // > 0: the neighbour is nearer
        // Nearer by up to a radius darkens; much nearer is a silhouette, not a crease.
        occlusion += clamp(dz / uWorldRadius, 0.0, 1.0) *
                     (1.0 - smoothstep(1.5 * uWorldRadius, 3.0 * uWorldRadius, dz));
    }
    oOcclusion = vec4(occlusion / 16.0, 0.0, 0.0, 1.0);
}
)";
}

std::string compositeFragment() {
    return std::string(kHeader) + kViewDepth + R"(
uniform sampler2D uColor;
uniform sampler2D uOcclusion;
uniform int uAmbientOcclusion;
uniform float uStrength;
uniform float uWorldRadius;
uniform sampler2D uContext;  // hidden spheres as points: colour, coverage in alpha
uniform float uContextAlpha; // 0: no context layer
layout(location = 0) out vec4 oColor; // premultiplied
vec4 withContext(vec4 c, ivec2 px) {
    if (uContextAlpha <= 0.0)
        return c;
    vec4 ctx = texelFetch(uContext, px, 0);
    float k = ctx.a * uContextAlpha;
    return c * (1.0 - k) + vec4(ctx.rgb * k, k);
}
void main() {
    ivec2 px = ivec2(gl_FragCoord.xy);
    vec4 c = texelFetch(uColor, px, 0);
    float d = texelFetch(uDepth, px, 0).r;
    if (uAmbientOcclusion == 0 || d >= 1.0) {
        oColor = withContext(c, px);
        return;
    }
    // 3 x 3 blur of the half-resolution occlusion over texels at a similar depth (not across
    // silhouettes): removes the grain and brings it back to full resolution.
    ivec2 size = textureSize(uDepth, 0);
    ivec2 half_ = textureSize(uOcclusion, 0);
    ivec2 base = px / 2;
    float z = viewDepth(d);
    float sum = 0.0, weight = 0.0;
    for (int j = -1; j <= 1; ++j)
        for (int i = -1; i <= 1; ++i) {
            ivec2 q = clamp(base + ivec2(i, j), ivec2(0), half_ - 1);
            float dq = texelFetch(uDepth, min(q * 2, size - 1), 0).r;
            float w = abs(viewDepth(dq) - z) < uWorldRadius ? 1.0 : 0.0;
            sum += w * texelFetch(uOcclusion, q, 0).r;
            weight += w;
        }
    float ao = 1.0 - uStrength * sum / max(weight, 1.0);
    oColor = withContext(vec4(c.rgb * ao, c.a), px);
}
)";
}

std::string downsampleFragment() {
    return std::string(kHeader) + R"(
uniform sampler2D uSource;
uniform int uFactor;
layout(location = 0) out vec4 oColor;
void main() {
    ivec2 base = ivec2(gl_FragCoord.xy) * uFactor;
    vec4 sum = vec4(0.0);
    for (int j = 0; j < uFactor; ++j)
        for (int i = 0; i < uFactor; ++i)
            sum += texelFetch(uSource, base + ivec2(i, j), 0);
    oColor = sum / float(uFactor * uFactor);
}
)";
}

std::string overlayVertex() {
    return std::string(kHeader) + R"(
layout(location = 0) in vec2 aPos;   // pixels, y down
layout(location = 1) in vec2 aUV;
layout(location = 2) in vec4 aColor; // straight alpha
uniform vec2 uViewport;
out vec2 vUV;
out vec4 vColor;
void main() {
    vUV = aUV;
    vColor = aColor;
    gl_Position = vec4(aPos.x / uViewport.x * 2.0 - 1.0, 1.0 - aPos.y / uViewport.y * 2.0, 0.0, 1.0);
}
)";
}

std::string overlayFragment() {
    return std::string(kHeader) + kColorMap + R"(
uniform int uMode; // 0 solid, 1 text, 2 colour map along v (v = t)
uniform sampler2D uFont;
in vec2 vUV;
in vec4 vColor;
layout(location = 0) out vec4 oColor; // premultiplied
void main() {
    vec4 c = vColor;
    if (uMode == 1)
        c.a *= texture(uFont, vUV).r;
    else if (uMode == 2)
        c.rgb = mapColor(vUV.y);
    oColor = vec4(c.rgb * c.a, c.a);
}
)";
}

} // namespace faultline::ui::gl::shaders
