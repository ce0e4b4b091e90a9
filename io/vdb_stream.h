// Every byte OpenVDB reads, through one stream buffer (io/ only). OpenVDB's io::File reads with its
// own std::ifstream, which returns zeros past the end of a truncated uncompressed file without a
// word (oiio_sphere.vdb cut in half loaded 6,521 of its 9,047 voxels); io::Stream reads from any
// std::istream, so here it reads from a buffer that throws at the end of the file, which makes every
// truncation an error wherever the cut is, and whose byte count is the reading progress. (io::Stream
// was once seen to spin on truncated files: that was reading zeros past the end; it now throws.)
// The metadata read (io/vdb_import.cpp, MetadataReader) seeks in it to the grids' offsets.
#pragma once

#include <cstdio>
#include <functional>
#include <memory>
#include <streambuf>
#include <string>

namespace brume {

class VdbFileBuf : public std::streambuf {
public:
    // progress(fraction read) is called whenever another whole percent has been read; optional.
    VdbFileBuf(const std::string& path, std::function<void(float)> progress);
    bool isOpen() const { return file_ != nullptr; }

    uint64_t fileSize() const { return fileSize_; }

protected:
    int_type underflow() override;  // throws std::runtime_error at the end of the file
    // Seeking (OpenVDB's grid descriptors hold offsets): within [0, size]; anything else fails (-1).
    pos_type seekoff(off_type off, std::ios_base::seekdir dir, std::ios_base::openmode which) override;
    pos_type seekpos(pos_type pos, std::ios_base::openmode which) override;

private:
    struct Close {
        void operator()(std::FILE* f) const { std::fclose(f); }
    };
    std::unique_ptr<std::FILE, Close> file_;
    std::function<void(float)> progress_;
    uint64_t read_ = 0;
    uint64_t fileSize_ = 0, filePos_ = 0;  // filePos_: the file offset just past the buffer's bytes
    int percent_ = -1;
    char buffer_[1 << 16];
};

}  // namespace brume
