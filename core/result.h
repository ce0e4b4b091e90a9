// Errors as values (no exit() or throw across library boundaries). An Error's message is one
// sentence a user can act on; for input files it reads "FILE: JSON-PATH: what is wrong".
#pragma once

#include <string>
#include <utility>
#include <variant>

namespace brume {

struct Error {
    std::string message;
    // The input asks for what cannot be done (too large for the device, say) and the user can fix
    // it: the command line exits 2 rather than 1.
    bool badInput = false;
};

template <class T>
class [[nodiscard]] Result {
public:
    Result(T value) : v_(std::move(value)) {}
    Result(Error e) : v_(std::move(e)) {}
    bool ok() const { return v_.index() == 0; }
    explicit operator bool() const { return ok(); }
    T& value() & { return std::get<0>(v_); }
    const T& value() const& { return std::get<0>(v_); }
    T&& value() && { return std::get<0>(std::move(v_)); }
    const Error& error() const { return std::get<1>(v_); }

private:
    std::variant<T, Error> v_;
};

template <>
class [[nodiscard]] Result<void> {
public:
    Result() = default;
    Result(Error e) : ok_(false), e_(std::move(e)) {}
    bool ok() const { return ok_; }
    explicit operator bool() const { return ok_; }
    const Error& error() const { return e_; }

private:
    bool ok_ = true;
    Error e_;
};

}  // namespace brume
