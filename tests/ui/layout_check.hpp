// Finds text a user cannot read in a frame's draw data: text cut off by the edge of its window,
// column or button, and text drawn over other text. It reads the glyph quads ImGui emitted (a
// quad whose texture coordinates are a glyph of the font atlas), so it sees every label, table
// cell and overlay, whoever drew it.
//
// - Cut off: a glyph that reaches past its draw command's clip rectangle horizontally (the GPU
//   scissor would cut it), or one ImGui trimmed on the CPU (RenderTextClipped: its texture
//   coordinates are a part of the glyph's).
// - Over other text: the visible parts of two glyphs of different runs of text in one window
//   overlap by more than a couple of pixels each way.
//
// - Wider than its window or column: ImGui measures every item it lays out, drawn or not, so a
//   window whose content reaches past its visible area (with no horizontal scrollbar), or a
//   table column whose content reaches past its edge, has something cut off even where the cut
//   falls between two words. The text nearest the edge is named.
//
// Vertical cuts are not reported: a scrolled panel cuts its rows at the top and bottom by design.
#pragma once

#include <imgui.h>
#include <imgui_internal.h> // ImDrawList::_OwnerName

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <unordered_set>
#include <utility>
#include <vector>

namespace faultline::test {

struct LayoutProblem {
    std::string window; // the draw list's owner
    std::string what;   // a sentence naming the text
};

namespace layout_detail {

struct Glyph {
    ImVec2 p0, p1;      // quad on screen
    ImVec4 clip;        // the draw command's clip rectangle
    unsigned codepoint; // the character
    bool trimmed;       // cut on the CPU (part of the glyph's texture only)
    int run;            // index of the run of text it belongs to (per draw list)
    unsigned order;     // where its quad starts in the draw list's index buffer
};

struct GlyphKey {
    float u, v;
    bool operator<(const GlyphKey& o) const { return u < o.u || (u == o.u && v < o.v); }
};

struct Atlas {
    std::map<GlyphKey, const ImFontGlyph*> byTopLeft, byBottomRight;
    Atlas() {
        for (const ImFont* font : ImGui::GetIO().Fonts->Fonts)
            for (const ImFontGlyph& g : font->Glyphs)
                if (g.Visible) {
                    byTopLeft[{g.U0, g.V0}] = &g;
                    byBottomRight[{g.U1, g.V1}] = &g;
                }
    }
};

inline std::string utf8(unsigned c) {
    std::string s;
    if (c < 0x80)
        s += static_cast<char>(c);
    else if (c < 0x800) {
        s += static_cast<char>(0xC0 | (c >> 6));
        s += static_cast<char>(0x80 | (c & 0x3F));
    } else {
        s += static_cast<char>(0xE0 | (c >> 12));
        s += static_cast<char>(0x80 | ((c >> 6) & 0x3F));
        s += static_cast<char>(0x80 | (c & 0x3F));
    }
    return s;
}

// The glyph quads of one draw list, in the order drawn, grouped into runs: consecutive glyphs on
// one baseline moving right.
inline std::vector<Glyph> glyphsOf(const ImDrawList& list, const Atlas& atlas) {
    std::vector<Glyph> out;
    const ImTextureID fontTexture = ImGui::GetIO().Fonts->TexID;
    int run = -1;
    float lastX = 0, lastBaseline = 0;
    unsigned lastOrder = 0;
    for (const ImDrawCmd& cmd : list.CmdBuffer) {
        if (cmd.UserCallback || cmd.TextureId != fontTexture)
            continue;
        // Triangle by triangle (other shapes may hold an odd number of them); a glyph is a quad
        // of two.
        for (unsigned e = 0; e + 3 <= cmd.ElemCount; e += 3) {
            if (e + 6 > cmd.ElemCount)
                break;
            const ImDrawIdx* idx = list.IdxBuffer.Data + cmd.IdxOffset + e;
            const unsigned i0 = cmd.VtxOffset + idx[0];
            // A glyph quad: indices 0 1 2 0 2 3 over four vertices in a row.
            if (idx[1] != idx[0] + 1 || idx[2] != idx[0] + 2 || idx[3] != idx[0] ||
                idx[4] != idx[0] + 2 || idx[5] != idx[0] + 3)
                continue;
            const ImDrawVert* v = list.VtxBuffer.Data + i0;
            if (v[0].pos.y != v[1].pos.y || v[1].pos.x != v[2].pos.x || v[2].pos.y != v[3].pos.y ||
                v[0].pos.x != v[3].pos.x)
                continue;
            const ImFontGlyph* g = nullptr;
            bool trimmed = false;
            if (auto it = atlas.byTopLeft.find({v[0].uv.x, v[0].uv.y});
                it != atlas.byTopLeft.end()) {
                g = it->second;
                trimmed = v[2].uv.x != g->U1; // cut on the right (cuts at the top or bottom
                                              // are a scrolled panel's edge, by design)
            } else if (auto jt = atlas.byBottomRight.find({v[2].uv.x, v[2].uv.y});
                       jt != atlas.byBottomRight.end()) {
                g = jt->second;
                trimmed = v[0].uv.x != g->U0; // cut on the left
            }
            if (!g)
                continue;
            const float height = v[2].pos.y - v[0].pos.y;
            const float scale = g->Y1 > g->Y0 ? height / (g->Y1 - g->Y0) : 1.0f;
            const float baseline = v[0].pos.y - g->Y0 * scale;
            // One run is one call's text: glyphs back to back in the index buffer, on one
            // baseline, moving right.
            const unsigned order = cmd.IdxOffset + e;
            if (run < 0 || order != lastOrder + 6 || std::abs(baseline - lastBaseline) > 0.5f ||
                v[0].pos.x < lastX - 1.0f)
                ++run;
            lastBaseline = baseline;
            lastX = v[0].pos.x;
            lastOrder = order;
            out.push_back(
                {v[0].pos, v[2].pos, cmd.ClipRect, g->Codepoint, trimmed, run, cmd.IdxOffset + e});
            e += 3; // the quad's second triangle
        }
    }
    return out;
}

inline std::string runText(const std::vector<Glyph>& glyphs, int run) {
    std::string s;
    for (const Glyph& g : glyphs)
        if (g.run == run)
            s += utf8(g.codepoint);
    return s;
}

} // namespace layout_detail

// The problems in the draw data of the last ImGui::Render().
inline std::vector<LayoutProblem> layoutProblems(const ImDrawData* data) {
    using namespace layout_detail;
    std::vector<LayoutProblem> problems;
    if (!data)
        return problems;
    const Atlas atlas;
    constexpr float kSlack = 1.5f;   // glyph quads carry a transparent pixel at their edges
    constexpr float kOverlap = 2.5f; // pixels each way before text counts as over other text
    for (int l = 0; l < data->CmdListsCount; ++l) {
        const ImDrawList& list = *data->CmdLists[l];
        const std::string window = list._OwnerName ? list._OwnerName : "?";
        const std::vector<Glyph> glyphs = glyphsOf(list, atlas);
        std::vector<int> reported;
        auto report = [&](int run, const std::string& why) {
            if (std::find(reported.begin(), reported.end(), run) != reported.end())
                return;
            reported.push_back(run);
            problems.push_back({window, "\"" + runText(glyphs, run) + "\" " + why});
        };
        for (const Glyph& g : glyphs) {
            if (g.trimmed)
                report(g.run, "is cut off (trimmed to its box)");
            else if (g.p1.x > g.clip.z + kSlack && g.p0.x < g.clip.z)
                report(g.run, "is cut off at the right edge of its window or column");
            else if (g.p0.x < g.clip.x - kSlack && g.p1.x > g.clip.x)
                report(g.run, "is cut off at the left edge of its window or column");
        }
        // Text under an opaque shape drawn after it (a button's frame over a label): each
        // triangle that is not a glyph, against the glyphs drawn before it whose visible
        // centre it covers, in a grid of 32-pixel buckets.
        {
            std::unordered_set<unsigned> glyphStarts;
            std::map<std::pair<int, int>, std::vector<int>> grid;
            auto bucket = [](float v) { return static_cast<int>(std::floor(v / 32.0f)); };
            std::vector<ImVec2> centre(glyphs.size());
            for (std::size_t k = 0; k < glyphs.size(); ++k) {
                const Glyph& g = glyphs[k];
                glyphStarts.insert(g.order);
                const float x0 = std::max(g.p0.x, g.clip.x), x1 = std::min(g.p1.x, g.clip.z);
                const float y0 = std::max(g.p0.y, g.clip.y), y1 = std::min(g.p1.y, g.clip.w);
                if (x1 - x0 < 1.0f || y1 - y0 < 1.0f || g.codepoint == ' ')
                    continue;
                centre[k] = ImVec2(0.5f * (x0 + x1), 0.5f * (y0 + y1));
                grid[{bucket(centre[k].x), bucket(centre[k].y)}].push_back(static_cast<int>(k));
            }
            auto inside = [](ImVec2 p, ImVec2 a, ImVec2 b, ImVec2 c) {
                const float d1 = (p.x - b.x) * (a.y - b.y) - (a.x - b.x) * (p.y - b.y);
                const float d2 = (p.x - c.x) * (b.y - c.y) - (b.x - c.x) * (p.y - c.y);
                const float d3 = (p.x - a.x) * (c.y - a.y) - (c.x - a.x) * (p.y - a.y);
                const bool neg = d1 < 0 || d2 < 0 || d3<0, pos = d1> 0 || d2 > 0 || d3 > 0;
                return !(neg && pos);
            };
            for (const ImDrawCmd& cmd : list.CmdBuffer) {
                if (cmd.UserCallback)
                    continue;
                for (unsigned e = 0; e + 3 <= cmd.ElemCount; e += 3) {
                    const unsigned at = cmd.IdxOffset + e;
                    if (glyphStarts.count(at)) {
                        e += 3;
                        continue;
                    }
                    const ImDrawIdx* idx = list.IdxBuffer.Data + at;
                    const ImDrawVert& a = list.VtxBuffer[cmd.VtxOffset + idx[0]];
                    const ImDrawVert& b = list.VtxBuffer[cmd.VtxOffset + idx[1]];
                    const ImDrawVert& c = list.VtxBuffer[cmd.VtxOffset + idx[2]];
                    // Opaque enough to hide what is under it (button frames are partly
                    // transparent).
                    auto opaque = [](ImU32 col) {
                        return ((col >> IM_COL32_A_SHIFT) & 0xFF) >= 100;
                    };
                    if (!opaque(a.col) || !opaque(b.col) || !opaque(c.col))
                        continue;
                    const float area = 0.5f * std::abs((b.pos.x - a.pos.x) * (c.pos.y - a.pos.y) -
                                                       (c.pos.x - a.pos.x) * (b.pos.y - a.pos.y));
                    if (area < 4.0f)
                        continue; // lines and edges, not a shape that hides text
                    const float bx0 =
                        std::max(std::min({a.pos.x, b.pos.x, c.pos.x}), cmd.ClipRect.x);
                    const float bx1 =
                        std::min(std::max({a.pos.x, b.pos.x, c.pos.x}), cmd.ClipRect.z);
                    const float by0 =
                        std::max(std::min({a.pos.y, b.pos.y, c.pos.y}), cmd.ClipRect.y);
                    const float by1 =
                        std::min(std::max({a.pos.y, b.pos.y, c.pos.y}), cmd.ClipRect.w);
                    if (bx1 <= bx0 || by1 <= by0)
                        continue;
                    for (int gx = bucket(bx0); gx <= bucket(bx1); ++gx)
                        for (int gy = bucket(by0); gy <= bucket(by1); ++gy) {
                            auto it = grid.find({gx, gy});
                            if (it == grid.end())
                                continue;
                            for (int k : it->second) {
                                const ImVec2 p = centre[k];
                                if (glyphs[k].order < at && p.x >= bx0 && p.x <= bx1 &&
                                    p.y >= by0 && p.y <= by1 && inside(p, a.pos, b.pos, c.pos))
                                    report(glyphs[k].run, "is hidden under a shape drawn over it");
                            }
                        }
                }
            }
        }

        // Text over text: sweep the visible parts of the glyphs by their left edge.
        struct Box {
            float x0, y0, x1, y1;
            int run;
        };
        std::vector<Box> boxes;
        for (const Glyph& g : glyphs) {
            Box b{std::max(g.p0.x, g.clip.x), std::max(g.p0.y, g.clip.y),
                  std::min(g.p1.x, g.clip.z), std::min(g.p1.y, g.clip.w), g.run};
            if (b.x1 - b.x0 > kOverlap && b.y1 - b.y0 > kOverlap && g.codepoint != ' ')
                boxes.push_back(b);
        }
        std::sort(boxes.begin(), boxes.end(),
                  [](const Box& a, const Box& b) { return a.x0 < b.x0; });
        std::vector<std::pair<int, int>> pairs;
        for (std::size_t a = 0; a < boxes.size(); ++a)
            for (std::size_t b = a + 1; b < boxes.size() && boxes[b].x0 < boxes[a].x1 - kOverlap;
                 ++b) {
                if (boxes[a].run == boxes[b].run)
                    continue;
                const float dy =
                    std::min(boxes[a].y1, boxes[b].y1) - std::max(boxes[a].y0, boxes[b].y0);
                if (dy <= kOverlap)
                    continue;
                const std::pair<int, int> p = std::minmax(boxes[a].run, boxes[b].run);
                if (std::find(pairs.begin(), pairs.end(), p) != pairs.end())
                    continue;
                pairs.push_back(p);
                problems.push_back({window, "\"" + runText(glyphs, p.first) + "\" and \"" +
                                                runText(glyphs, p.second) + "\" overlap"});
            }
    }
    // Content wider than its window or table column (ImGui's own measure of what it laid out).
    const ImGuiContext& g = *ImGui::GetCurrentContext();
    constexpr float kWider = 2.0f;
    for (const ImGuiWindow* w : g.Windows) {
        if (!w->Active || w->Hidden || w->ScrollbarX || w->SkipItems ||
            (w->Flags & (ImGuiWindowFlags_Tooltip | ImGuiWindowFlags_AlwaysAutoResize)))
            continue;
        // Children without padding of their own are a multi-line text box's (its text scrolls
        // sideways with the cursor, as in any editor) or a scrolling table's rows (the columns
        // are checked below).
        if ((w->Flags & ImGuiWindowFlags_ChildWindow) &&
            !(w->Flags & ImGuiWindowFlags_AlwaysUseWindowPadding))
            continue;
        const float over = w->DC.CursorMaxPos.x - w->InnerClipRect.Max.x;
        if (over > kWider) {
            // Name the text that reaches furthest right: usually what is cut.
            std::string nearest;
            if (w->DrawList) {
                const std::vector<Glyph> glyphs = glyphsOf(*w->DrawList, atlas);
                const Glyph* far = nullptr;
                for (const Glyph& g : glyphs)
                    if (!far || g.p1.x > far->p1.x)
                        far = &g;
                if (far)
                    nearest = " (furthest right: \"" + runText(glyphs, far->run) + "\")";
            }
            problems.push_back({w->Name, "has content " + std::to_string(int(over)) +
                                             " px wider than the window" + nearest});
        }
    }
    for (int n = 0; n < g.Tables.GetMapSize(); ++n) {
        ImGuiTable* t = const_cast<ImGuiContext&>(g).Tables.TryGetMapData(n);
        if (!t || t->LastFrameActive != g.FrameCount || !t->OuterWindow)
            continue;
        for (int c = 0; c < t->ColumnsCount; ++c) {
            const ImGuiTableColumn& col = t->Columns[c];
            if (!col.IsEnabled || !col.IsVisibleX)
                continue;
            const float content = std::max(
                {col.ContentMaxXFrozen, col.ContentMaxXUnfrozen, col.ContentMaxXHeadersUsed});
            const float over = content - col.ClipRect.Max.x;
            if (over > kWider) {
                const char* name = ImGui::TableGetColumnName(t, c);
                problems.push_back({t->OuterWindow->Name,
                                    "table column " + std::to_string(c) +
                                        (name && *name ? std::string(" \"") + name + "\"" : "") +
                                        " has content " + std::to_string(int(over)) +
                                        " px wider than the column"});
            }
        }
    }
    return problems;
}

} // namespace faultline::test
