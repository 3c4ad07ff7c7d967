// TEMPORARY until the VTK readers land.
#include "core/io/vtk_legacy.hpp"
#include "core/io/vtk_xml.hpp"
#include "core/io/input_error.hpp"
namespace faultline::core {
bool looksLikeVtkLegacy(std::string_view head) { return head.substr(0, 14) == "# vtk DataFile"; }
Frame parseVtkLegacy(const std::string& path, std::string_view) { throw InputError(path, "VTK legacy not available yet"); }
bool looksLikeVtkXml(std::string_view head) { return head.find("<VTKFile") != std::string_view::npos; }
bool looksLikeVtkCollection(std::string_view head) { return head.find("\"Collection\"") != std::string_view::npos; }
Frame parseVtkXml(const std::string& path, std::string_view) { throw InputError(path, "VTK XML not available yet"); }
std::vector<CollectionEntry> parseVtkCollection(const std::string& path, std::string_view) { throw InputError(path, "pvd not available yet"); }
}
