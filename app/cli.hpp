// The faultline command line: one function per subcommand, each returning the exit code.
#pragma once

#include <string>
#include <vector>

namespace faultline::app {

using Args = std::vector<std::string>;

int runInfo(const Args& args);
int runRenderData(const Args& args); // developer tool until `render` lands
int runGui(const Args& args);
void printUsage();

} // namespace faultline::app
