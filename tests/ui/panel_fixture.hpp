// A workbench on a small lattice, run headless: the fixture of the panel tests.
#pragma once

#include "../core/test_files.hpp"
#include "headless_ui.hpp"

#include <gtest/gtest.h>

#include <memory>
#include <string>

namespace faultline::test {

class PanelTest : public ::testing::Test {
  protected:
    void SetUp() override {
        ui::WorkbenchOptions options;
        options.stateDir = stateDir();
        options.autosaveSeconds = 0; // every frame that changed something (tests)
        m_wb = std::make_unique<ui::Workbench>(session, options);
        headless.frames(wb(), 2);
    }
    void TearDown() override { m_wb.reset(); }

    virtual std::string stateDir() { return {}; } // no journal or autosave unless asked

    ui::Workbench& wb() { return *m_wb; }
    // Clicks `item` of the main view's colour popup, opening the popup first when it is not
    // open, and runs two frames: what is emitted then is what the click did.
    void clickInColourPopup(const std::string& item) {
        if (!headless.has(wb(), item)) {
            headless.click(wb(), "view.colour.main");
            headless.frames(wb(), 2);
        }
        headless.clearEmitted();
        headless.click(wb(), item);
        headless.frames(wb(), 2);
    }
    // Presses Faults > Candidates > Find in visible, waits for the background job and draws
    // two frames: the list shows what was found.
    void findCandidates() {
        headless.click(wb(), "candidates.find");
        headless.settle(wb());
        headless.frames(wb(), 2);
    }
    // Opens the lattice (3 frames of 64 spheres) the way a user does, in the background.
    void openLattice() {
        wb().opener().openData({writeLattice(dir.file("lattice.dump"))});
        headless.settle(wb());
        ASSERT_NE(session.dataset(), nullptr);
        ASSERT_NE(wb().mainDisplay(), nullptr);
        ASSERT_NE(wb().mainDisplay()->frame, nullptr);
        headless.clearEmitted();
    }
    // A second workbench on a session of its own that opens `file`, as after a restart.
    struct Reopened {
        core::Session session;
        ui::Workbench wb;
        Reopened() : wb(session, ui::WorkbenchOptions{}) {}
    };
    std::unique_ptr<Reopened> reopen(const std::string& file) {
        auto r = std::make_unique<Reopened>();
        headless.frames(r->wb, 2);
        r->wb.opener().openSession(file);
        headless.settle(r->wb);
        return r;
    }
    // Opens a combo (marked `combo`) and picks its item (marked `item`), with nothing emitted
    // before; then lets the background work settle.
    void pickFromCombo(const std::string& combo, const std::string& item) {
        headless.clearEmitted();
        headless.click(wb(), combo);
        headless.frames(wb(), 2);
        headless.click(wb(), item);
        headless.settle(wb());
    }
    std::size_t visible() const {
        const ui::ViewDisplay* d = m_wb->mainDisplay();
        return d && d->visibility ? d->visibility->visibleCount : 0;
    }

    TempDir dir;
    core::Session session;
    HeadlessUi headless;

  private:
    std::unique_ptr<ui::Workbench> m_wb;
};

} // namespace faultline::test
