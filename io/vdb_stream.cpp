#include "vdb_stream.h"

#include <algorithm>
#include <filesystem>
#include <stdexcept>

namespace brume {

VdbFileBuf::VdbFileBuf(const std::string& path, std::function<void(float)> progress)
    : file_(std::fopen(path.c_str(), "rb")), progress_(std::move(progress)) {
    std::error_code ec;
    size_ = std::max<uint64_t>(1, std::filesystem::file_size(path, ec));
}

VdbFileBuf::int_type VdbFileBuf::underflow() {
    const size_t n = file_ ? std::fread(buffer_, 1, sizeof buffer_, file_.get()) : 0;
    if (n == 0) throw std::runtime_error("unexpected end of file: it is truncated");
    read_ += n;
    setg(buffer_, buffer_, buffer_ + n);
    const int percent = static_cast<int>(std::min<uint64_t>(100, read_ * 100 / size_));
    if (progress_ && percent > percent_) {
        percent_ = percent;
        progress_(static_cast<float>(percent) / 100.0f);
    }
    return traits_type::to_int_type(buffer_[0]);
}

}  // namespace brume
