// The message of the exception a call throws ("" when it throws none): for tests that check
// what an error says, not only that there was one.
#pragma once

#include <functional>
#include <string>

namespace pathlet::test {

template <class Error>
std::string error_text(const std::function<void()>& f) {
    try {
        f();
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

}  // namespace pathlet::test
