// LammpsDumpWriter: writes frames one after another into one multi-frame LAMMPS text dump,
// plain or gzip (zlib), with values in shortest round-trip form so our reader gets them back
// exactly.
#pragma once

#include "core/model/frame.hpp"

#include <string>
#include <vector>

namespace faultline::core {

class LammpsDumpWriter {
  public:
    // Opens (truncates) `path`. `gzipLevel` 0 writes plain text, 1-9 gzip through zlib.
    // Throws std::runtime_error naming the path when the file cannot be opened.
    LammpsDumpWriter(std::string path, int gzipLevel = 0);
    ~LammpsDumpWriter();
    LammpsDumpWriter(const LammpsDumpWriter&) = delete;
    LammpsDumpWriter& operator=(const LammpsDumpWriter&) = delete;

    // Appends `frame` with `columns` in that order: "id", "x", "y", "z", "radius" are the
    // frame's own columns, any other name one of its attributes (asserted to exist).
    // ITEM: BOX BOUNDS comes from frame.box (written as given, "ff" or "pp" per axis).
    void write(const Frame& frame, const std::vector<std::string>& columns);

    // Flushes and closes; throws std::runtime_error on a write error. The destructor closes too
    // but cannot report errors.
    void close();

    const std::string& path() const { return m_path; }

  private:
    void put(const std::string& text);
    std::string m_path;
    void* m_gz = nullptr;        // gzFile
    std::FILE* m_file = nullptr; // plain output
    bool m_failed = false;
};

} // namespace faultline::core
