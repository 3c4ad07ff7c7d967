#include "ui/panels/panels.hpp"

namespace faultline::ui {

std::vector<std::unique_ptr<Panel>> createPanels() {
    std::vector<std::unique_ptr<Panel>> p;
    p.push_back(makeViewportsPanel());
    p.push_back(makeDataPanel());
    p.push_back(makeBoxesPanel());
    p.push_back(makeThresholdsPanel());
    p.push_back(makeHistogramsPanel());
    p.push_back(makeFaultsPanel());
    p.push_back(makeSurfacesPanel());
    p.push_back(makeTimelinePanel());
    return p;
}

} // namespace faultline::ui
