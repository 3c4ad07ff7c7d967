// The workbench's panels (one class per file in ui/panels/), made in the order of panel_ids.
#pragma once

#include "ui/context/panel_context.hpp"

#include <memory>
#include <vector>

namespace faultline::ui {

std::vector<std::unique_ptr<Panel>> createPanels();

std::unique_ptr<Panel> makeDataPanel();
std::unique_ptr<Panel> makeHistogramsPanel();
std::unique_ptr<Panel> makeBoxesPanel();
std::unique_ptr<Panel> makeThresholdsPanel();
std::unique_ptr<Panel> makeFaultsPanel();
std::unique_ptr<Panel> makeSurfacesPanel();
std::unique_ptr<Panel> makeTimelinePanel();
std::unique_ptr<Panel> makeViewportsPanel();

// Sections plugged into panels through PanelExtensions.
void addFaultCandidatesSection(PanelExtensions& extensions); // Faults: candidates to accept
void addFaultMetricsSection(PanelExtensions& extensions);    // Faults: metrics over time

} // namespace faultline::ui
