// The faultline command line: one function per subcommand, each returning the exit code.
#pragma once

#include <string>
#include <vector>

namespace faultline::core {
class Session;
}

namespace faultline::app {

using Args = std::vector<std::string>;

int runInfo(const Args& args);
int runGenerate(const Args& args);
int runRenderData(const Args& args); // developer tool until `render` lands
int runGui(const Args& args);
int runReplay(const Args& args);
int runRender(const Args& args);
int runMerge(const Args& args);

// Replaces this process with faultline-app (beside this executable) on the same arguments;
// returns only when that fails, with the exit code to use.
int runFullApp(int argc, char** argv);

// Adds the ops that need layers above core (render) to a session.
void registerAppOps(core::Session& session);
void printUsage();

} // namespace faultline::app
