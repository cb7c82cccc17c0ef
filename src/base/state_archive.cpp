// Binary state of a run for checkpoints (state_archive.hpp).
#include <lagfsi/state_archive.hpp>

namespace lagfsi {

void StateArchive::check_left(std::uint64_t n) const {
  if (n > buf_.size() - pos_) throw CheckpointError("it ends too early (cut off, or written by another version)");
}

void StateArchive::raw(void* p, size_t n) {
  if (!loading_) {
    buf_.append(static_cast<const char*>(p), n);
    return;
  }
  check_left(n);
  if (n > 0) std::memcpy(p, buf_.data() + pos_, n);
  pos_ += n;
}

void StateArchive::io(std::string& s) {
  std::uint64_t n = s.size();
  io(n);
  if (loading_) {
    check_left(n);
    s.assign(buf_.data() + pos_, n);
    pos_ += n;
  } else {
    buf_.append(s);
  }
}

void StateArchive::section(const std::string& name) {
  std::string s = name;
  io(s);
  if (loading_ && s != name)
    throw CheckpointError("found '" + s.substr(0, 60) + "' where '" + name +
                          "' was expected (the case or the program differ from the checkpoint's)");
}

}  // namespace lagfsi
