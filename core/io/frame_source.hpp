// Where frames live on disk and how to read one: format detection by content, indexing of a
// file into frame locations, and loading a frame (merging LAMMPS per-processor pieces).
#pragma once

#include "core/model/frame.hpp"

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace faultline::core {

enum class FileFormat { LammpsDump, VtkLegacy, VtkXml, VtkCollection, Table, Xyz, MercuryData };

std::string_view formatName(FileFormat format);

// By content (first bytes, inflated when gzip), not by extension. Throws InputError when the
// file cannot be read or is of no known format.
FileFormat detectFormat(const std::string& path);

// A byte range of one file holding (part of) a frame.
struct FramePiece {
    std::string path;
    std::uint64_t offset = 0;
    std::uint64_t length = 0; // 0: the whole file
    std::uint64_t firstLine = 1;
};

struct FrameLocation {
    FileFormat format = FileFormat::Table;
    std::int64_t timestep = 0;
    double time = 0.0;               // from a .pvd collection, else the timestep
    std::uint64_t particleCount = 0; // when the index knows it (LAMMPS), else 0
    std::vector<FramePiece> pieces;  // several for LAMMPS per-processor files
    // LIGGGHTS' dump custom/vtk: the run_boundingBox_N.vtk written beside this frame's file,
    // read as the frame's simulation box (its files hold none); empty: none.
    std::string boxPath;
};

// The last run of digits in a file's name before its extensions ("run_49600.vtk": 49600).
std::optional<std::int64_t> numberInFileName(const std::string& path);
// A legacy VTK RECTILINEAR_GRID file: LIGGGHTS' dump custom/vtk writes run_boundingBox_N.vtk
// beside each frame; a series skips them.
bool isVtkRectilinearGrid(const std::string& path);
// The box such a file spans (its coordinates' smallest and largest along each axis; known, no
// periodic axis). Throws InputError naming the file and line of anything else.
SimulationBox readVtkRectilinearBox(const std::string& path);

// Every frame one file holds (a .pvd collection expands to the files it lists).
// `partial` (optional): a multi-frame text file (LAMMPS dump, XYZ, MercuryDPM) that ends inside
// a frame after complete ones keeps them, and `partial` says what was left out (else an error).
std::vector<FrameLocation> indexDataFile(const std::string& path, std::string* partial = nullptr);

// Reads one frame; throws InputError with the file and position of any fault.
Frame loadFrame(const FrameLocation& location);

// Concatenates frames of the same columns (LAMMPS per-processor pieces) into one.
Frame mergeFrames(std::vector<Frame>&& pieces, const std::string& pathForErrors);

} // namespace faultline::core
