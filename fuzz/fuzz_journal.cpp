// Journal text -> parse, then apply every command that touches no file, check expectations.
// Only InputError and CommandError may come out.
#include "core/io/input_error.hpp"
#include "core/session/journal.hpp"

#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace faultline::core;
    const std::string text(reinterpret_cast<const char*>(data), size);
    Session session;
    std::vector<JournalLine> lines;
    try {
        lines = parseJournal(text, "fuzz.jsonl", session);
    } catch (const InputError&) {
        return 0;
    }
    for (const auto& line : lines) {
        try {
            if (line.isExpectation) {
                const std::string kind = line.value["expect"].get<std::string>();
                if (kind != "file_exists" && kind != "image")
                    checkExpectation(session, line.value);
                continue;
            }
            const std::string op = line.value["op"].get<std::string>();
            if (op.rfind("data.", 0) == 0 || op.rfind("export.", 0) == 0 || op == "session.save" ||
                op == "render" || op == "batch")
                continue; // files: not this target's business
            session.apply(line.value);
        } catch (const CommandError&) {
        } catch (const InputError&) {
        }
    }
    return 0;
}
