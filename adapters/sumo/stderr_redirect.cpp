#include "stderr_redirect.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace orch {

void StderrRedirect::engage(Target target) {
  if (saved_ >= 0) return;
  std::fflush(stderr);
  int fd = -1;
  if (target == Target::Silence) {
    const char* keep = std::getenv("ORCH_SUMO_STDERR");
    if (keep && std::strcmp(keep, "1") == 0) return;
    fd = ::open("/dev/null", O_WRONLY | O_CLOEXEC);
  } else {
    FILE* tmp = std::tmpfile();
    if (tmp) {
      fd = ::dup(::fileno(tmp));  // keeps the anonymous file alive
      std::fclose(tmp);
    }
  }
  if (fd < 0) return;
  saved_ = ::dup(STDERR_FILENO);
  ::dup2(fd, STDERR_FILENO);
  if (target == Target::Capture)
    file_ = fd;
  else
    ::close(fd);
}

std::string StderrRedirect::release() {
  if (saved_ < 0) return "";
  std::fflush(stderr);
  ::dup2(saved_, STDERR_FILENO);
  ::close(saved_);
  saved_ = -1;
  std::string text;
  if (file_ >= 0) {
    if (::lseek(file_, 0, SEEK_SET) == 0) {
      char buf[4096];
      ssize_t n;
      while ((n = ::read(file_, buf, sizeof buf)) > 0 && text.size() < 65536) text.append(buf, static_cast<std::size_t>(n));
    }
    ::close(file_);
    file_ = -1;
  }
  return text;
}

}  // namespace orch
