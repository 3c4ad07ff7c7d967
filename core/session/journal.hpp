// Journals (JOURNAL.md): JSON Lines of commands and expectations. Parsing checks every line
// before anything runs; replay applies commands to a Session and checks each expectation.
#pragma once

#include "core/session/session.hpp"

#include <optional>
#include <string>
#include <vector>

namespace faultline::core {

struct JournalLine {
    std::size_t line = 0; // 1-based line in the file
    Json value;
    bool isExpectation = false;
};

// Throws InputError naming the line of a malformed line, an unknown op or expectation.
std::vector<JournalLine> parseJournal(const std::string& text, const std::string& path,
                                      const Session& session);

// Checks one expectation against the session; nullopt when it holds, else "expected .., actual ..".
std::optional<std::string> checkExpectation(Session& session, const Json& expectation);
bool isKnownExpectation(const std::string& name);

struct ReplayOptions {
    std::vector<std::string> data; // --data: re-target data.open to these paths
    std::string outDir;            // --out: where outputs go (default: the journal's folder)
    FrameSelection frames;         // --frames A:B, --shard K/N: per-frame work on these only
    // --strict: a threshold, colouring or surface colour naming a variable the data lacks stops
    // the replay (without it, a warning: the analysis would silently keep every sphere).
    bool strict = false;
};

struct ReplayFailure {
    std::size_t line = 0;
    std::string message;
};

struct ReplayReport {
    std::size_t commands = 0;
    std::size_t expectations = 0;
    std::vector<ReplayFailure> failures; // failed expectations, and the command that stopped it
    bool stopped = false;                // a command failed; later lines did not run
    std::vector<ReplayFailure> warnings; // variables the data lacks (errors with --strict)
    bool ok() const { return failures.empty(); }
};

// Runs a journal file headless. Throws InputError when the file cannot be read or parsed.
ReplayReport replayJournal(const std::string& path, const ReplayOptions& options, Session& session);

} // namespace faultline::core
