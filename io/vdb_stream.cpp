#include "vdb_stream.h"

#include <algorithm>
#include <filesystem>
#include <stdexcept>

#include <sys/types.h>

namespace brume {

VdbFileBuf::VdbFileBuf(const std::string& path, std::function<void(float)> progress)
    : file_(std::fopen(path.c_str(), "rb")), progress_(std::move(progress)) {
    std::error_code ec;
    fileSize_ = std::filesystem::file_size(path, ec);
    if (ec) fileSize_ = 0;
}

VdbFileBuf::int_type VdbFileBuf::underflow() {
    const size_t n = file_ ? std::fread(buffer_, 1, sizeof buffer_, file_.get()) : 0;
    if (n == 0) throw std::runtime_error("unexpected end of file: it is truncated");
    read_ += n;
    filePos_ += n;
    setg(buffer_, buffer_, buffer_ + n);
    const int percent = static_cast<int>(std::min<uint64_t>(100, read_ * 100 / std::max<uint64_t>(1, fileSize_)));
    if (progress_ && percent > percent_) {
        percent_ = percent;
        progress_(static_cast<float>(percent) / 100.0f);
    }
    return traits_type::to_int_type(buffer_[0]);
}

VdbFileBuf::pos_type VdbFileBuf::seekoff(off_type off, std::ios_base::seekdir dir, std::ios_base::openmode which) {
    const pos_type fail(off_type(-1));
    if (!file_ || !(which & std::ios_base::in)) return fail;
    const int64_t here = static_cast<int64_t>(filePos_) - static_cast<int64_t>(egptr() - gptr());
    const int64_t base = dir == std::ios_base::beg ? 0 : dir == std::ios_base::cur ? here : static_cast<int64_t>(fileSize_);
    const int64_t target = base + static_cast<int64_t>(off);
    if (target < 0 || static_cast<uint64_t>(target) > fileSize_) return fail;
    if (dir == std::ios_base::cur && off == 0) return pos_type(target);  // tellg: keep the buffer
    if (fseeko(file_.get(), static_cast<off_t>(target), SEEK_SET) != 0) return fail;
    filePos_ = static_cast<uint64_t>(target);
    setg(buffer_, buffer_, buffer_);
    return pos_type(target);
}

VdbFileBuf::pos_type VdbFileBuf::seekpos(pos_type pos, std::ios_base::openmode which) {
    return seekoff(off_type(pos), std::ios_base::beg, which);
}

}  // namespace brume
