// libFuzzer target: the case loader on arbitrary bytes. What must hold for any file:
//   - load() returns a Case or throws CaseError, nothing else (no crash, no hang, no other
//     exception, no UB under the sanitizers);
//   - a CaseError's message is one printable line of bounded length (quoted input is cut, and
//     control characters are escaped), so it can be printed as the one line a user gets.
// The bytes reach the loader as a file, as a user's would: an in-memory file (memfd) named by
// its /proc/self/fd path.
#include <sys/mman.h>
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "casefile/casefile.hpp"

namespace {

void fail(const char* what, const std::string& message) {
  std::fprintf(stderr, "fuzz_casefile: %s: %s\n", what, message.c_str());
  std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const int fd = memfd_create("case.json", 0);
  if (fd < 0) return 0;
  for (size_t done = 0; done < size;) {
    const ssize_t n = write(fd, data + done, size - done);
    if (n <= 0) {
      close(fd);
      return 0;
    }
    done += size_t(n);
  }
  const std::string path = "/proc/self/fd/" + std::to_string(fd);
  try {
    (void)glrc::casefile::load(path);
  } catch (const glrc::casefile::CaseError& e) {
    const std::string message = e.what();
    if (message.empty()) fail("empty message", message);
    if (message.size() > 1000) fail("message longer than 1000 characters", message.substr(0, 200));
    for (unsigned char ch : message)
      if (ch < 0x20 || ch == 0x7f) fail("control character in the message", message);
  } catch (const std::exception& e) {
    fail("not a CaseError", e.what());
  }
  close(fd);
  return 0;
}
