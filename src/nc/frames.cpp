#include <cutroute/nc/frames.hpp>

#include "nc/block_scanner.hpp"

namespace cutroute::nc {

namespace {

struct LineClass {
  bool frame = false;
  bool end = false;
};

LineClass classify(std::string_view line) {
  LineClass c;
  const auto r = detail::scan_block(line, [&](const detail::Word& w) {
    if (w.letter != 'N' && w.letter != 'O') c.frame = true;
    if (w.letter == 'M' && (w.value == 2.0 || w.value == 30.0)) c.end = true;
  });
  if (r.error != detail::ScanError::none || r.tape_mark) return {};
  c.end = c.end && c.frame;
  return c;
}

}  // namespace

bool is_frame(std::string_view line) { return classify(line).frame; }
bool ends_program(std::string_view line) { return classify(line).end; }

std::size_t count_frames(std::string_view program) {
  std::size_t n = 0;
  std::size_t pos = 0;
  while (pos < program.size()) {
    const auto line = detail::next_line(program, pos);
    const LineClass c = classify(line.text);
    if (c.frame) ++n;
    if (c.end) break;
    pos = line.next;
  }
  return n;
}

}  // namespace cutroute::nc
