// Data panel, "Strain from motion": the strain variables of the session (strain.add), each with
// its reference and cutoff and a Remove, and a form that adds more: cumulative (since a frame)
// or incremental (frames before each frame), the neighbour cutoff (automatic: 1.5 x the median
// diameter, shown), a prefix. The variables then appear in every variable menu; a main view
// in plain colour is coloured by the new shear strain in the same step (one undo).
#pragma once

#include "ui/context/panel_context.hpp"

#include <memory>
#include <string>

namespace faultline::ui {

class StrainSection {
  public:
    void draw(PanelContext& wb);

  private:
    bool m_incremental = true;
    int m_sinceFrame = 0;
    int m_offset = 4; // frames before each frame; follows the data until edited
    bool m_offsetEdited = false;
    std::weak_ptr<core::Dataset> m_offsetData; // the data the offset was chosen for (not held)
    double m_cutoff = 0;                       // 0: automatic
    std::string m_prefix = "inc_";
    // The automatic cutoff's hint, worked out once per frame shown (a median of up to 65,536
    // radii: not at every redraw).
    std::weak_ptr<const core::Frame> m_autoFor;
    std::string m_autoText = "auto";
    bool m_prefixEdited = false;
};

} // namespace faultline::ui
