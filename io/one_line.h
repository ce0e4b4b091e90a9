#pragma once
// Text from outside Brume (a JSON key, an OpenVDB exception quoting bytes of a corrupt file) placed in
// an error sentence: control characters are written escaped (\n, \t, \r, else \xHH) so the sentence
// stays on one line. Bytes from 0x80 up are left as they are (a JSON writer replaces invalid UTF-8).
#include <string>
#include <string_view>

namespace brume {

inline std::string escapeControlCharacters(std::string_view text) {
    static constexpr char kHex[] = "0123456789abcdef";
    std::string out;
    out.reserve(text.size());
    for (const char c : text) {
        const auto u = static_cast<unsigned char>(c);
        if (c == '\n') out += "\\n";
        else if (c == '\t') out += "\\t";
        else if (c == '\r') out += "\\r";
        else if (u < 0x20 || u == 0x7f) {
            out += "\\x";
            out += kHex[u >> 4];
            out += kHex[u & 15];
        } else out += c;
    }
    return out;
}

}  // namespace brume
