// scan_block(): splits one G-code line into its words (letter + number), shared by the frame
// counter and the reader so that both agree on what a block contains.
#pragma once

#include <charconv>
#include <cstddef>
#include <string>
#include <string_view>

namespace cutroute::nc::detail {

struct Word {
  char letter = 0;         // upper case
  double value = 0.0;      // as written (no unit conversion)
  std::size_t column = 0;  // 1-based column of the letter, for messages
};

enum class ScanError { none, unclosed_comment, nested_comment, missing_number, malformed_number, number_out_of_range, unsupported_character };

// Largest |number| a word may carry: 10^9 mm is a thousand kilometres, 10^9 s of dwell thirty years;
// beyond it sums of lengths and times could overflow to infinity.
inline constexpr double kMaxWordMagnitude = 1.0e9;

struct ScanResult {
  ScanError error = ScanError::none;
  std::size_t column = 0;  // 1-based column of the problem
  char letter = 0;         // the word letter concerned (missing/malformed number)
  char character = 0;      // the offending character (unsupported_character)
  bool tape_mark = false;  // the line is a '%' line (never a frame)
};

inline bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\f' || c == '\v'; }
inline bool is_digit(char c) { return c >= '0' && c <= '9'; }
inline bool is_alpha(char c) { return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z'); }
inline char upper(char c) { return (c >= 'a' && c <= 'z') ? static_cast<char>(c - 'a' + 'A') : c; }

// The line starting at `pos` (without terminator) and the position of the next line; LF, CRLF
// and lone CR all end a line.
struct LineSpan {
  std::string_view text;
  std::size_t next = 0;
};
inline LineSpan next_line(std::string_view program, std::size_t pos) {
  std::size_t eol = pos;
  const std::size_t n = program.size();
  while (eol < n && program[eol] != '\n' && program[eol] != '\r') ++eol;
  std::size_t next = eol;
  if (next < n) next += (program[next] == '\r' && next + 1 < n && program[next + 1] == '\n') ? 2 : 1;
  return {program.substr(pos, eol - pos), next};
}

// Calls on_word(const Word&) for each word of `line` (no line terminator), left to right.
// Comments "( ... )" and "; ..." are skipped; a '%' first on the line makes it a tape mark.
// Numbers are RS274 decimals: optional sign, digits with at most one '.', no exponent; blanks
// between the letter and the number are allowed (dxf2gcode writes "X  62.125").
// Stops at the first problem and reports it; on_word has then seen the words before it.
template <class OnWord>
ScanResult scan_block(std::string_view line, OnWord&& on_word) {
  ScanResult r;
  const char* const begin = line.data();
  const char* p = begin;
  const char* const end = begin + line.size();
  while (p < end && is_blank(*p)) ++p;
  if (p < end && *p == '%') {
    r.tape_mark = true;
    return r;
  }
  if (p < end && *p == '/') ++p;  // block delete: the block is still part of the program
  while (p < end && is_blank(*p)) ++p;
  const char* const first = p;
  while (p < end) {
    const char c = *p;
    if (is_blank(c)) {
      ++p;
      continue;
    }
    if (c == ';') break;
    if (c == '(') {
      const char* q = p + 1;
      while (q < end && *q != ')' && *q != '(') ++q;
      // Read as ending at the first ')', "(a (b) c)" left " c)" to be read as a word C.
      if (q < end && *q == '(') {
        r.error = ScanError::nested_comment;
        r.column = static_cast<std::size_t>(q - begin) + 1;
        return r;
      }
      if (q == end) {
        r.error = ScanError::unclosed_comment;
        r.column = static_cast<std::size_t>(p - begin) + 1;
        return r;
      }
      p = q + 1;
      continue;
    }
    if (!is_alpha(c) && !(c == ':' && p == first)) {
      r.error = ScanError::unsupported_character;
      r.column = static_cast<std::size_t>(p - begin) + 1;
      r.character = c;
      return r;
    }
    Word w;
    w.letter = c == ':' ? 'O' : upper(c);  // ":1000" is a Fanuc program number, as O1000
    w.column = static_cast<std::size_t>(p - begin) + 1;
    ++p;
    while (p < end && is_blank(*p)) ++p;
    bool negative = false;
    bool sign = false;
    if (p < end && (*p == '+' || *p == '-')) {
      negative = *p == '-';
      sign = true;
      ++p;
    }
    // RS274/NGC ignores blanks anywhere outside comments, inside a number too ("X 2 0.5" is X20.5):
    // a blank run followed by a digit or a point continues the number.
    const char* num = p;
    std::string joined;  // the number's characters without its blanks, when it has any
    bool gapped = false;
    int digits = 0;
    int dots = 0;
    while (p < end) {
      if (is_blank(*p)) {
        const char* q = p;
        while (q < end && is_blank(*q)) ++q;
        if (digits + dots == 0 || q == end || !(is_digit(*q) || *q == '.')) break;
        if (!gapped) joined.assign(num, p);
        gapped = true;
        p = q;
        continue;
      }
      if (!is_digit(*p) && *p != '.') break;
      if (*p == '.')
        ++dots;
      else
        ++digits;
      if (gapped) joined += *p;
      ++p;
    }
    if (digits == 0) {
      r.error = (!sign && p == num && (p == end || is_alpha(*p) || is_blank(*p) || *p == '(' || *p == ';'))
                    ? ScanError::missing_number
                    : ScanError::malformed_number;
      r.column = w.column;
      r.letter = w.letter;
      return r;
    }
    // "1e5" is an exponent, which RS274 numbers do not have; it is not the words 1 and E5.
    const bool exponent =
        p + 1 < end && (*p == 'e' || *p == 'E') && (is_digit(p[1]) || p[1] == '+' || p[1] == '-');
    const bool bad_follower =
        exponent || (p < end && !(is_alpha(*p) || is_blank(*p) || *p == '(' || *p == ';'));
    if (dots > 1 || bad_follower) {
      r.error = ScanError::malformed_number;
      r.column = w.column;
      r.letter = w.letter;
      return r;
    }
    double v = 0.0;
    const char* const nb = gapped ? joined.data() : num;
    const char* const ne = gapped ? joined.data() + joined.size() : p;
    const auto fc = std::from_chars(nb, ne, v, std::chars_format::fixed);
    // Out of double's range (hundreds of digits) is too large like 20 digits, or below the
    // smallest double: then it is zero for every length and time read here.
    if (fc.ec == std::errc::result_out_of_range && fc.ptr == ne) {
      const std::string_view number(nb, static_cast<std::size_t>(ne - nb));
      const bool integer_digits = number.find_first_not_of("0.") < number.find('.');
      if (integer_digits) {
        r.error = ScanError::number_out_of_range;
        r.column = w.column;
        r.letter = w.letter;
        return r;
      }
      v = 0.0;
    } else if (fc.ec != std::errc{} || fc.ptr != ne) {
      r.error = ScanError::malformed_number;
      r.column = w.column;
      r.letter = w.letter;
      return r;
    }
    if (v > kMaxWordMagnitude) {
      r.error = ScanError::number_out_of_range;
      r.column = w.column;
      r.letter = w.letter;
      return r;
    }
    w.value = negative ? -v : v;
    on_word(static_cast<const Word&>(w));
  }
  return r;
}

// What a failed scan_block() found, as a message naming the column ("" when it did not fail).
inline std::string scan_message(const ScanResult& s) {
  const std::string col = " (column " + std::to_string(s.column) + ")";
  switch (s.error) {
    case ScanError::unclosed_comment:
      return "comment '(' is not closed on its line" + col;
    case ScanError::nested_comment:
      return "comment opened inside a comment" + col + ": controllers refuse nested comments";
    case ScanError::missing_number:
      return std::string("word ") + s.letter + " has no number" + col;
    case ScanError::malformed_number:
      return std::string("malformed number after ") + s.letter + col;
    case ScanError::number_out_of_range:
      return std::string("number after ") + s.letter + " beyond +-1e9" + col;
    case ScanError::unsupported_character: {
      static constexpr char kHex[] = "0123456789ABCDEF";
      const auto byte = static_cast<unsigned char>(s.character);
      std::string c = (byte >= 32 && byte < 127) ? std::string(1, s.character)
                                                 : std::string("\\x") + kHex[byte >> 4] + kHex[byte & 15];  // ESC: \x1B
      return "unsupported character '" + c + "'" + col +
             ": parameters, expressions and other extensions are not read";
    }
    case ScanError::none:
      break;
  }
  return {};
}

}  // namespace cutroute::nc::detail
