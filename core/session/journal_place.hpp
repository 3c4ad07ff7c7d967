// A background action's place in the journal (Session::reserveAction), held while the object
// lives: settle() records the action there once it worked; destroyed unsettled (the action
// failed or was cancelled), the place records nothing and the lines behind it are written.
#pragma once

#include "core/session/session.hpp"

#include <cstdint>

namespace faultline::core {

class JournalPlace {
  public:
    explicit JournalPlace(Session& session)
        : m_session(session), m_place(session.reserveAction()) {}
    ~JournalPlace() { m_session.dropAction(m_place); } // nothing once settled
    JournalPlace(const JournalPlace&) = delete;
    JournalPlace& operator=(const JournalPlace&) = delete;

    std::uint64_t place() const { return m_place; }
    // Throws CommandError for an op that is no action (the place then stays open until drop).
    void settle(const Json& cmd) { m_session.settleAction(m_place, cmd); }

  private:
    Session& m_session;
    std::uint64_t m_place;
};

} // namespace faultline::core
