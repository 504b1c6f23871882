// The one definition of a frame (NC block) that the G-code writer and reader both count by.
#pragma once

#include <cstddef>
#include <string_view>

namespace cutroute::nc {

// A frame is one block the controller executes: a line holding at least one word other than
// the sequence number N and the program number O (motion, G, M, S, F, T ... words all count).
// Not frames: blank lines, comment-only lines, '%' tape marks, lines holding only N or O
// numbers, and anything after the block that ends the program (M2/M30). Table 1's n is the number of frames
// of the whole program (docs/FRAMES.md has an example). A line the scanner rejects (malformed) is not a
// frame; the reader reports it as an error anyway.
bool is_frame(std::string_view line);

// True when the line is a frame holding M2 or M30 (the program ends after it).
bool ends_program(std::string_view line);

// Frames of a whole program text (LF, CRLF or CR line ends), stopping after the program end.
std::size_t count_frames(std::string_view program);

}  // namespace cutroute::nc
