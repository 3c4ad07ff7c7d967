#include "ui/workbench/movie_export.hpp"

#include "core/session/journal_place.hpp"

#include <filesystem>

namespace faultline::ui {

namespace fs = std::filesystem;

MovieExport::~MovieExport() { stop(); }

void MovieExport::stop() {
    m_place.reset(); // nothing written in its place
    m_sequence.reset();
}

void MovieExport::start(const SequenceRequest& request, core::Json command) {
    stop();
    m_sequence = std::make_unique<FrameSequence>(m_session, request);
    m_command = std::move(command);
    m_place = std::make_unique<core::JournalPlace>(m_session);
}

std::pair<std::size_t, std::size_t> MovieExport::progress() const {
    return m_sequence ? std::pair{m_sequence->done(), m_sequence->total()}
                      : std::pair<std::size_t, std::size_t>{0, 0};
}

const std::string& MovieExport::path() const {
    static const std::string kNone;
    return m_sequence ? m_sequence->path() : kNone;
}

MovieExport::Step MovieExport::step() {
    if (!m_sequence)
        return {};
    try {
        m_sequence->step(false); // renders the next frame if it is loaded
    } catch (const std::exception& e) {
        stop();
        return {State::Failed, e.what()};
    }
    if (!m_sequence->finished())
        return {State::Running, {}};
    Step done{State::Written, "Wrote " + m_sequence->path() + " (" +
                                  std::to_string(m_sequence->total()) + " frames)"};
    try {
        m_place->settle(m_command);
    } catch (const std::exception& e) {
        done.message += "; not in the journal: " + std::string(e.what());
    }
    m_place.reset(); // unsettled: the place records nothing
    m_sequence.reset();
    return done;
}

std::string MovieExport::cancel() {
    if (!m_sequence)
        return {};
    const std::size_t done = m_sequence->done();
    const std::string name = fs::path(m_sequence->path()).filename().string();
    stop();
    return "Movie cancelled after " + std::to_string(done) + " frames (" + name + " holds those)";
}

} // namespace faultline::ui
