#pragma once
// Checks of exception messages: the call throws std::invalid_argument naming what it should.

#include <boost/test/unit_test.hpp>

#include <exception>
#include <functional>
#include <initializer_list>
#include <stdexcept>
#include <string>

namespace deepcheck::test {

/// Runs f, which must throw std::invalid_argument whose message contains every one of `parts`.
inline void checkThrows(const std::function<void()>& f, std::initializer_list<std::string> parts) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    const std::string message = e.what();
    BOOST_TEST_MESSAGE("message: " << message);
    for (const std::string& part : parts) {
      BOOST_CHECK_MESSAGE(message.find(part) != std::string::npos, "message lacks '" << part << "': " << message);
    }
    return;
  } catch (const std::exception& e) {
    BOOST_ERROR("expected std::invalid_argument, got another exception: " << e.what());
    return;
  }
  BOOST_ERROR("expected std::invalid_argument, nothing was thrown");
}

}  // namespace deepcheck::test
