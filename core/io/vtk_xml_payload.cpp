#include "core/io/vtk_xml_payload.hpp"

#include "core/io/base64.hpp"
#include "core/io/input_error.hpp"

#include <fast_float/fast_float.h>
#include <lz4.h>
#include <lzma.h>
#include <zlib.h>

#include <sys/mman.h>

#include <cmath>
#include <cstdlib>
#include <optional>

namespace faultline::core::detail {

namespace {

inline bool isBlank(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }

// liblzma's allocations. An .xz header names the dictionary size the decoder allocates (8 MB for
// VTK's default preset, up to the 256 MB memlimit in a forged or corrupted header), while a VTK
// block writes at most its block size into it: large ones are mapped on demand, so an untouched
// dictionary costs address space, never memory writes (glibc's malloc maps them too; sanitizer
// allocators would write shadow memory for all of it, parse after parse).
constexpr std::size_t kHeader = 64;           // keeps liblzma's alignment; holds the size
constexpr std::size_t kMapAbove = 1ull << 20; // smaller ones come from malloc
void* lzmaAlloc(void*, std::size_t count, std::size_t size) {
    if (size != 0 && count > (SIZE_MAX - kHeader) / size)
        return nullptr;
    const std::size_t bytes = count * size + kHeader;
    void* block = nullptr;
    if (bytes > kMapAbove) {
        block = mmap(nullptr, bytes, PROT_READ | PROT_WRITE,
                     MAP_PRIVATE | MAP_ANONYMOUS | MAP_NORESERVE, -1, 0);
        if (block == MAP_FAILED)
            return nullptr;
    } else if (!(block = std::malloc(bytes))) {
        return nullptr;
    }
    *static_cast<std::size_t*>(block) = bytes;
    return static_cast<char*>(block) + kHeader;
}
void lzmaFree(void*, void* ptr) {
    if (!ptr)
        return;
    void* block = static_cast<char*>(ptr) - kHeader;
    const std::size_t bytes = *static_cast<std::size_t*>(block);
    if (bytes > kMapAbove)
        munmap(block, bytes);
    else
        std::free(block);
}
const lzma_allocator kLzmaAllocator{lzmaAlloc, lzmaFree, nullptr};

std::string describe(const XmlArraySource& s) {
    return "DataArray '" + s.name + "' (line " + std::to_string(s.tagLine) + ")";
}

void decodeAscii(const std::string& path, const XmlArraySource& s, std::uint64_t count,
                 bool requireFinite, std::vector<double>& out) {
    const std::string_view t = s.text;
    if (count > 0 && 2 * count - 1 > t.size())
        throw InputError(path, InputError::Where::Line, s.textLine,
                         describe(s) + ": expected " + std::to_string(count) +
                             " values, its text is only " + std::to_string(t.size()) +
                             " bytes long");
    out.resize(count);
    const bool integral = vtkScalarIsIntegral(s.type);
    std::size_t p = 0;
    std::uint64_t line = s.textLine;
    auto skipBlanks = [&] {
        while (p < t.size() && isBlank(t[p])) {
            if (t[p] == '\n')
                ++line;
            ++p;
        }
    };
    for (std::uint64_t i = 0; i < count; ++i) {
        skipBlanks();
        const std::size_t start = p;
        while (p < t.size() && !isBlank(t[p]))
            ++p;
        const std::string_view tok = t.substr(start, p - start);
        auto bad = [&](const char* expected) {
            throw InputError(
                path, InputError::Where::Line, line,
                describe(s) + ": value " + std::to_string(i + 1) + " of " + std::to_string(count) +
                    ": expected " + expected + ", found " +
                    (tok.empty() ? std::string("the end of the array") : quoteForError(tok)));
        };
        if (tok.empty())
            bad("a number");
        double v;
        const char* b = tok.data() + (tok[0] == '+');
        auto r = fast_float::from_chars(b, tok.data() + tok.size(), v);
        if (r.ec != std::errc() || r.ptr != tok.data() + tok.size())
            bad(integral ? "an integer" : "a number");
        if (integral && v != std::trunc(v))
            bad("an integer");
        if (requireFinite && !std::isfinite(static_cast<float>(v)))
            bad("a finite number");
        out[i] = v;
    }
    skipBlanks();
    if (p < t.size()) {
        std::size_t end = p;
        while (end < t.size() && !isBlank(t[end]))
            ++end;
        throw InputError(path, InputError::Where::Line, line,
                         describe(s) + ": more values than the " + std::to_string(count) +
                             " expected, found " + quoteForError(t.substr(p, end - p)));
    }
}

// The bytes of a binary array: raw appended bytes, or base64 text decoded as it is read.
class PayloadStream {
  public:
    PayloadStream(std::string_view data, bool base64, std::size_t fileOffset)
        : m_raw(data), m_fileOffset(fileOffset) {
        if (base64)
            m_base64.emplace(data);
    }
    std::uint64_t maxRemaining() const {
        return m_base64 ? m_base64->maxRemainingBytes() : m_raw.size() - m_pos;
    }
    std::size_t fileOffset() const {
        return m_fileOffset + (m_base64 ? m_base64->position() : m_pos);
    }
    // Reads exactly n bytes, else returns an error message.
    std::optional<std::string> read(unsigned char* dst, std::size_t n) {
        if (!m_base64) {
            if (n > m_raw.size() - m_pos)
                return "needs " + std::to_string(n) + " more bytes, only " +
                       std::to_string(m_raw.size() - m_pos) + " remain";
            std::copy(m_raw.begin() + static_cast<std::ptrdiff_t>(m_pos),
                      m_raw.begin() + static_cast<std::ptrdiff_t>(m_pos + n), dst);
            m_pos += n;
            return std::nullopt;
        }
        const std::size_t got = m_base64->decode(dst, n);
        if (m_base64->failed()) {
            m_errorOffset = m_fileOffset + m_base64->errorOffset();
            return m_base64->error();
        }
        if (got < n)
            return "needs " + std::to_string(n) + " more bytes, the base64 data ends after " +
                   std::to_string(got);
        return std::nullopt;
    }
    std::optional<std::size_t> errorOffset() const { return m_errorOffset; }

  private:
    std::string_view m_raw;
    std::size_t m_pos = 0;
    std::optional<Base64Decoder> m_base64;
    std::size_t m_fileOffset;
    std::optional<std::size_t> m_errorOffset;
};

class BinaryDecoder {
  public:
    BinaryDecoder(const std::string& path, const XmlEncoding& e, const XmlArraySource& s,
                  PayloadStream& stream)
        : m_path(path), m_enc(e), m_src(s), m_stream(stream) {}

    [[noreturn]] void fail(const std::string& message) const {
        const std::size_t at = m_stream.errorOffset().value_or(m_stream.fileOffset());
        throw InputError(m_path, InputError::Where::Byte, at, describe(m_src) + ": " + message);
    }

    void read(unsigned char* dst, std::size_t n, const char* what) {
        if (auto err = m_stream.read(dst, n))
            fail(std::string(what) + ": " + *err);
    }

    std::uint64_t readWord(const char* what) {
        unsigned char b[8];
        read(b, m_enc.headerBytes, what);
        std::uint64_t v = 0;
        for (std::size_t i = 0; i < m_enc.headerBytes; ++i) {
            const std::size_t k = m_enc.bigEndian ? i : m_enc.headerBytes - 1 - i;
            v = (v << 8) | b[k];
        }
        return v;
    }

    // The array's packed bytes, `expected` of them.
    std::vector<unsigned char> payload(std::uint64_t expected) {
        return m_enc.compressor != XmlEncoding::Compressor::None ? inflateBlocks(expected)
                                                                 : plain(expected);
    }

  private:
    std::vector<unsigned char> plain(std::uint64_t expected) {
        const std::uint64_t declared = readWord("size header");
        if (declared != expected)
            fail("its size header declares " + std::to_string(declared) + " bytes, expected " +
                 std::to_string(expected));
        if (expected > m_stream.maxRemaining())
            fail("declares " + std::to_string(expected) + " bytes, only " +
                 std::to_string(m_stream.maxRemaining()) + " remain");
        std::vector<unsigned char> bytes(expected);
        read(bytes.data(), bytes.size(), "data");
        return bytes;
    }

    std::vector<unsigned char> inflateBlocks(std::uint64_t expected) {
        const std::uint64_t blocks = readWord("compression header");
        const std::uint64_t blockSize = readWord("compression header");
        const std::uint64_t lastSize = readWord("compression header");
        if (blocks > m_stream.maxRemaining() / m_enc.headerBytes)
            fail("compression header declares " + std::to_string(blocks) +
                 " blocks, more than the data can hold");
        std::vector<std::uint64_t> sizes(blocks);
        std::uint64_t compressedTotal = 0;
        for (auto& c : sizes) {
            c = readWord("compression header");
            if (c > m_stream.maxRemaining())
                fail("a compressed block of " + std::to_string(c) + " bytes is declared, only " +
                     std::to_string(m_stream.maxRemaining()) + " remain");
            compressedTotal += c;
            if (compressedTotal > m_stream.maxRemaining())
                fail("compressed blocks total more than the " +
                     std::to_string(m_stream.maxRemaining()) + " bytes that remain");
        }
        std::uint64_t total = 0;
        if (blocks > 0) {
            if (blockSize == 0 || lastSize > blockSize)
                fail("bad compression header: block size " + std::to_string(blockSize) +
                     ", last block size " + std::to_string(lastSize));
            if (blocks - 1 > (1ull << 56) / blockSize)
                fail("compression header declares an impossible size");
            total = (blocks - 1) * blockSize + (lastSize ? lastSize : blockSize);
        }
        if (total != expected)
            fail("compression header declares " + std::to_string(total) +
                 " uncompressed bytes, expected " + std::to_string(expected));
        std::vector<unsigned char> out, compressed;
        for (std::uint64_t k = 0; k < blocks; ++k) {
            const std::uint64_t size = (k + 1 == blocks && lastSize) ? lastSize : blockSize;
            // A header may not make us allocate more than the block's codec can produce from
            // its compressed bytes.
            if (size > sizes[k] * maxRatio() + 64)
                fail(std::string(codecName()) + " block " + std::to_string(k) + " claims " +
                     std::to_string(size) + " bytes from " + std::to_string(sizes[k]) +
                     " compressed bytes, more than " + codecName() + " can produce");
            compressed.resize(sizes[k]);
            read(compressed.data(), compressed.size(), "compressed block");
            const std::size_t old = out.size();
            out.resize(old + size);
            std::string why;
            const std::uint64_t produced = decompress(compressed, out.data() + old, size, why);
            if (!why.empty() || produced != size)
                fail(std::string(codecName()) + " block " + std::to_string(k) +
                     " is corrupt or does not decompress to the " + std::to_string(size) +
                     " bytes its header declares" +
                     (why.empty() ? " (it gives " + std::to_string(produced) + ")"
                                  : " (" + why + ")"));
        }
        return out;
    }

    const char* codecName() const {
        switch (m_enc.compressor) {
        case XmlEncoding::Compressor::LZ4:
            return "LZ4";
        case XmlEncoding::Compressor::LZMA:
            return "LZMA";
        default:
            return "zlib";
        }
    }
    // Uncompressed bytes per compressed byte at most: zlib's deflate 1032:1; LZ4 255:1; xz has
    // no small bound (a run of zeros packs ~7000:1), so a generous one that still caps what a
    // forged header can make us allocate at a few MB per KB of file.
    std::uint64_t maxRatio() const {
        switch (m_enc.compressor) {
        case XmlEncoding::Compressor::LZ4:
            return 256;
        case XmlEncoding::Compressor::LZMA:
            return 16384;
        default:
            return kMaxInflateRatio;
        }
    }
    // Decompresses one block into exactly `size` bytes at `to`; the bytes produced, or `why`.
    std::uint64_t decompress(const std::vector<unsigned char>& in, unsigned char* to,
                             std::uint64_t size, std::string& why) const {
        switch (m_enc.compressor) {
        case XmlEncoding::Compressor::LZ4: {
            if (in.size() > std::uint64_t(LZ4_MAX_INPUT_SIZE) || size > std::uint64_t(INT32_MAX)) {
                why = "block too large for LZ4";
                return 0;
            }
            const int n =
                LZ4_decompress_safe(reinterpret_cast<const char*>(in.data()),
                                    reinterpret_cast<char*>(to), int(in.size()), int(size));
            if (n < 0)
                why = "LZ4: malformed block";
            return n < 0 ? 0 : std::uint64_t(n);
        }
        case XmlEncoding::Compressor::LZMA: {
            std::uint64_t memlimit = 256ull << 20; // a preset-9 dictionary needs 65 MB
            std::size_t inPos = 0, outPos = 0;
            const lzma_ret rc = lzma_stream_buffer_decode(&memlimit, 0, &kLzmaAllocator, in.data(),
                                                          &inPos, in.size(), to, &outPos, size);
            if (rc != LZMA_OK)
                why = rc == LZMA_BUF_ERROR ? "LZMA: the stream is truncated or larger than declared"
                      : rc == LZMA_FORMAT_ERROR   ? "LZMA: not an .xz stream"
                      : rc == LZMA_MEMLIMIT_ERROR ? "LZMA: needs more than 256 MB to decode"
                      : rc == LZMA_MEM_ERROR      ? "LZMA: out of memory for the block's dictionary"
                                                  : "LZMA: corrupt data";
            return outPos;
        }
        default: {
            uLongf produced = static_cast<uLongf>(size);
            const int rc = uncompress(to, &produced, in.data(), static_cast<uLong>(in.size()));
            if (rc != Z_OK)
                why = std::string("zlib: ") + zError(rc);
            return produced;
        }
        }
    }

    const std::string& m_path;
    const XmlEncoding& m_enc;
    const XmlArraySource& m_src;
    PayloadStream& m_stream;
};

} // namespace

void decodeXmlArray(const std::string& path, const XmlEncoding& encoding,
                    const XmlArraySource& source, std::uint64_t count, bool requireFinite,
                    std::vector<double>& out) {
    if (source.format == XmlArraySource::Format::Ascii)
        return decodeAscii(path, source, count, requireFinite, out);

    std::string_view data = source.text;
    std::size_t fileOffset = source.textOffset;
    bool base64 = true;
    if (source.format == XmlArraySource::Format::Appended) {
        if (!encoding.haveAppended)
            throw InputError(path, InputError::Where::Line, source.tagLine,
                             describe(source) + " is appended, but the file has no <AppendedData>");
        if (source.appendedOffset > encoding.appended.size())
            throw InputError(path, InputError::Where::Line, source.tagLine,
                             describe(source) + ": offset " +
                                 std::to_string(source.appendedOffset) + " is beyond the " +
                                 std::to_string(encoding.appended.size()) +
                                 " bytes of appended data");
        data = encoding.appended.substr(source.appendedOffset);
        fileOffset = encoding.appendedOffset + source.appendedOffset;
        base64 = encoding.appendedBase64;
    }
    const std::uint64_t expected = vtkPackedBytes(source.type, count);
    PayloadStream stream(data, base64, fileOffset);
    BinaryDecoder decoder(path, encoding, source, stream);
    const std::vector<unsigned char> bytes = decoder.payload(expected);
    out.resize(count);
    unpackVtkValues(bytes.data(), count, source.type, encoding.bigEndian, out.data());
    if (requireFinite) {
        const std::size_t bad = firstNonFiniteAsFloat(out.data(), count);
        if (bad < count)
            throw InputError(path, InputError::Where::Byte, fileOffset,
                             describe(source) + ": value " + std::to_string(bad + 1) +
                                 " is not a finite number (" + std::to_string(out[bad]) + ")");
    }
}

} // namespace faultline::core::detail
