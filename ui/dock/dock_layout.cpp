#include "ui/dock/dock_layout.hpp"

#include "ui/dock/panel_ids.hpp"

#include <algorithm>
#include <functional>

namespace faultline::ui {

using nlohmann::json;

namespace {

constexpr int kLayoutVersion = 1;
constexpr int kMaxDepth = 16;
constexpr float kMinRatio = 0.05f, kMaxRatio = 0.95f;

std::unique_ptr<DockNode> leaf(std::vector<std::string> tabs) {
    auto n = std::make_unique<DockNode>();
    n->active = tabs.empty() ? std::string() : tabs.front();
    n->tabs = std::move(tabs);
    return n;
}

std::unique_ptr<DockNode> split(SplitAxis axis, float ratio, std::unique_ptr<DockNode> a,
                                std::unique_ptr<DockNode> b) {
    auto n = std::make_unique<DockNode>();
    n->split = axis;
    n->ratio = ratio;
    n->first = std::move(a);
    n->second = std::move(b);
    return n;
}

std::unique_ptr<DockNode> cloneNode(const DockNode& n) {
    auto c = std::make_unique<DockNode>();
    c->id = n.id;
    c->split = n.split;
    c->ratio = n.ratio;
    c->tabs = n.tabs;
    c->active = n.active;
    if (n.first)
        c->first = cloneNode(*n.first);
    if (n.second)
        c->second = cloneNode(*n.second);
    return c;
}

void forEach(DockNode& n, const std::function<void(DockNode&)>& f) {
    f(n);
    if (n.first)
        forEach(*n.first, f);
    if (n.second)
        forEach(*n.second, f);
}

json nodeJson(const DockNode& n) {
    if (n.isLeaf())
        return {{"tabs", n.tabs}, {"active", n.active}};
    return {{"split", n.split == SplitAxis::Horizontal ? "h" : "v"},
            {"ratio", n.ratio},
            {"a", nodeJson(*n.first)},
            {"b", nodeJson(*n.second)}};
}

// Parses a node; throws std::runtime_error with the reason. Panels are checked by the caller.
std::unique_ptr<DockNode> parseNode(const json& j, int depth) {
    if (depth > kMaxDepth)
        throw std::runtime_error("nested too deeply");
    if (!j.is_object())
        throw std::runtime_error("a node must be an object");
    if (j.contains("split")) {
        const json& s = j["split"];
        if (!s.is_string() || (s != "h" && s != "v"))
            throw std::runtime_error("\"split\" must be \"h\" or \"v\"");
        float ratio = 0.5f;
        if (j.contains("ratio")) {
            if (!j["ratio"].is_number())
                throw std::runtime_error("\"ratio\" must be a number");
            ratio = static_cast<float>(j["ratio"].get<double>());
            if (!(ratio == ratio))
                ratio = 0.5f;
        }
        if (!j.contains("a") || !j.contains("b"))
            throw std::runtime_error("a split needs \"a\" and \"b\"");
        return split(s == "h" ? SplitAxis::Horizontal : SplitAxis::Vertical,
                     std::clamp(ratio, kMinRatio, kMaxRatio), parseNode(j["a"], depth + 1),
                     parseNode(j["b"], depth + 1));
    }
    if (!j.contains("tabs") || !j["tabs"].is_array())
        throw std::runtime_error("an area needs a \"tabs\" array");
    std::vector<std::string> tabs;
    for (const json& t : j["tabs"]) {
        if (!t.is_string())
            throw std::runtime_error("tabs must be panel names");
        tabs.push_back(t.get<std::string>());
    }
    auto n = leaf(std::move(tabs));
    if (j.contains("active") && j["active"].is_string())
        n->active = j["active"].get<std::string>();
    return n;
}

} // namespace

DockLayout::DockLayout() : m_root(leaf({})) { m_root->id = nextId(); }

DockLayout::DockLayout(const DockLayout& other)
    : m_root(cloneNode(*other.m_root)), m_settings(other.m_settings), m_nextId(other.m_nextId) {}

DockLayout& DockLayout::operator=(const DockLayout& other) {
    if (this != &other) {
        m_root = cloneNode(*other.m_root);
        m_settings = other.m_settings;
        m_nextId = other.m_nextId;
    }
    return *this;
}

int DockLayout::nextId() { return m_nextId++; }

DockLayout DockLayout::defaultLayout() {
    using namespace panel_ids;
    DockLayout l;
    auto left = leaf({kData, kBoxes, kThresholds});
    auto centre = split(SplitAxis::Vertical, 0.87f, leaf({kViewports}), leaf({kTimeline}));
    auto right = split(SplitAxis::Vertical, 0.46f, leaf({kHistograms}), leaf({kFaults, kSurfaces}));
    l.m_root = split(SplitAxis::Horizontal, 0.2f, std::move(left),
                     split(SplitAxis::Horizontal, 0.75f, std::move(centre), std::move(right)));
    forEach(*l.m_root, [&](DockNode& n) { n.id = l.nextId(); });
    return l;
}

DockLayout DockLayout::defaultLayout(float windowWidth) {
    if (!(windowWidth > 0) || windowWidth >= kCompactWidth)
        return defaultLayout();
    using namespace panel_ids;
    DockLayout l;
    auto side = leaf({kData, kBoxes, kThresholds, kHistograms, kFaults, kSurfaces});
    auto centre = split(SplitAxis::Vertical, 0.8f, leaf({kViewports}), leaf({kTimeline}));
    const float ratio = std::clamp(260.0f / windowWidth, 0.2f, 0.5f);
    l.m_root = split(SplitAxis::Horizontal, ratio, std::move(side), std::move(centre));
    forEach(*l.m_root, [&](DockNode& n) { n.id = l.nextId(); });
    return l;
}

std::optional<DockLayout>
DockLayout::fromJson(const json& doc, const std::vector<std::string>& known, std::string* why) {
    auto fail = [&](const std::string& reason) -> std::optional<DockLayout> {
        if (why)
            *why = reason;
        return std::nullopt;
    };
    if (!doc.is_object() || !doc.contains("root"))
        return fail("not a dock layout (no \"root\")");
    if (doc.contains("version") &&
        (!doc["version"].is_number_integer() || doc["version"].get<int>() > kLayoutVersion))
        return fail("a newer dock layout version");
    DockLayout l;
    try {
        l.m_root = parseNode(doc["root"], 0);
    } catch (const std::exception& e) {
        return fail(e.what());
    }
    // Drop unknown and repeated panels, fix active tabs, number the nodes.
    std::vector<std::string> seen;
    forEach(*l.m_root, [&](DockNode& n) {
        n.id = l.nextId();
        if (!n.isLeaf())
            return;
        std::vector<std::string> kept;
        for (auto& t : n.tabs)
            if (std::find(known.begin(), known.end(), t) != known.end() &&
                std::find(seen.begin(), seen.end(), t) == seen.end()) {
                kept.push_back(t);
                seen.push_back(t);
            }
        n.tabs = std::move(kept);
        if (std::find(n.tabs.begin(), n.tabs.end(), n.active) == n.tabs.end())
            n.active = n.tabs.empty() ? std::string() : n.tabs.front();
    });
    l.collapseEmpty();
    if (doc.contains("panels") && doc["panels"].is_object())
        for (auto& [k, v] : doc["panels"].items())
            if (std::find(known.begin(), known.end(), k) != known.end())
                l.m_settings[k] = v;
    return l;
}

json DockLayout::toJson() const {
    json doc = {{"version", kLayoutVersion}, {"root", nodeJson(*m_root)}};
    if (!m_settings.empty()) {
        json panels = json::object();
        for (const auto& [k, v] : m_settings)
            panels[k] = v;
        doc["panels"] = panels;
    }
    return doc;
}

std::vector<DockNode*> DockLayout::areas() {
    std::vector<DockNode*> out;
    forEach(*m_root, [&](DockNode& n) {
        if (n.isLeaf())
            out.push_back(&n);
    });
    return out;
}

DockNode* DockLayout::node(int id) {
    DockNode* found = nullptr;
    forEach(*m_root, [&](DockNode& n) {
        if (n.id == id)
            found = &n;
    });
    return found;
}

DockNode* DockLayout::areaOf(const std::string& panel) {
    for (DockNode* a : areas())
        if (std::find(a->tabs.begin(), a->tabs.end(), panel) != a->tabs.end())
            return a;
    return nullptr;
}

bool DockLayout::contains(const std::string& panel) const {
    return const_cast<DockLayout*>(this)->areaOf(panel) != nullptr;
}

void DockLayout::collapseEmpty() {
    // Replace every split that has an empty leaf child by its other child (repeat until none).
    std::function<std::unique_ptr<DockNode>(std::unique_ptr<DockNode>)> fix =
        [&](std::unique_ptr<DockNode> n) -> std::unique_ptr<DockNode> {
        if (n->isLeaf())
            return n;
        n->first = fix(std::move(n->first));
        n->second = fix(std::move(n->second));
        const bool firstEmpty = n->first->isLeaf() && n->first->tabs.empty();
        const bool secondEmpty = n->second->isLeaf() && n->second->tabs.empty();
        if (firstEmpty)
            return std::move(n->second);
        if (secondEmpty)
            return std::move(n->first);
        return n;
    };
    m_root = fix(std::move(m_root));
}

bool DockLayout::movePanel(const std::string& panel, int areaId, DropSide side, float share) {
    DockNode* target = node(areaId);
    if (!target || !target->isLeaf())
        return false;
    DockNode* source = areaOf(panel);
    if (source == target && (side == DropSide::Centre || target->tabs.size() == 1))
        return false;
    if (source) {
        std::erase(source->tabs, panel);
        if (source->active == panel)
            source->active = source->tabs.empty() ? std::string() : source->tabs.front();
    }
    if (side == DropSide::Centre) {
        target->tabs.push_back(panel);
        target->active = panel;
    } else {
        // The target leaf becomes a split of (its old content, a new area with the panel).
        auto old = std::make_unique<DockNode>();
        old->id = target->id;
        old->tabs = std::move(target->tabs);
        old->active = std::move(target->active);
        auto fresh = leaf({panel});
        fresh->id = nextId();
        target->id = nextId();
        target->tabs.clear();
        target->active.clear();
        share = std::clamp(share, kMinRatio, kMaxRatio);
        const bool before = side == DropSide::Left || side == DropSide::Top;
        target->split = (side == DropSide::Left || side == DropSide::Right) ? SplitAxis::Horizontal
                                                                            : SplitAxis::Vertical;
        target->ratio = before ? share : 1.0f - share;
        target->first = before ? std::move(fresh) : std::move(old);
        target->second = before ? std::move(old) : std::move(fresh);
    }
    collapseEmpty();
    return true;
}

bool DockLayout::closePanel(const std::string& panel) {
    DockNode* a = areaOf(panel);
    if (!a)
        return false;
    std::erase(a->tabs, panel);
    if (a->active == panel)
        a->active = a->tabs.empty() ? std::string() : a->tabs.front();
    collapseEmpty();
    return true;
}

void DockLayout::openPanel(const std::string& panel) {
    if (contains(panel)) {
        setActive(panel);
        return;
    }
    // Where the default layout puts it: next to the first of its default neighbours still open.
    DockLayout def = defaultLayout();
    if (DockNode* home = def.areaOf(panel))
        for (const auto& neighbour : home->tabs)
            if (neighbour != panel)
                if (DockNode* a = areaOf(neighbour)) {
                    a->tabs.push_back(panel);
                    a->active = panel;
                    return;
                }
    auto all = areas();
    if (all.size() == 1 && all.front()->tabs.empty()) {
        all.front()->tabs = {panel};
        all.front()->active = panel;
        return;
    }
    // Otherwise a new area on the right of everything.
    auto old = std::move(m_root);
    auto fresh = leaf({panel});
    fresh->id = nextId();
    m_root = split(SplitAxis::Horizontal, 0.78f, std::move(old), std::move(fresh));
    m_root->id = nextId();
}

void DockLayout::setActive(const std::string& panel) {
    if (DockNode* a = areaOf(panel))
        a->active = panel;
}

json& DockLayout::panelSettings(const std::string& panel) {
    json& s = m_settings[panel];
    if (!s.is_object())
        s = json::object();
    return s;
}

const json* DockLayout::panelSettings(const std::string& panel) const {
    auto it = m_settings.find(panel);
    return it == m_settings.end() ? nullptr : &it->second;
}

} // namespace faultline::ui
