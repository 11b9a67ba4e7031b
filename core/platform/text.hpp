// Text from outside vivv — a program's answers and standard error, paths, names — on its way
// into a message, a report or the terminal. report.json, junit.xml and report.html must be
// UTF-8 (nlohmann's dump throws on anything else, after every case has computed), a shortened
// quote must not end in half a character, and a program's escape sequences must not reach the
// user's terminal as commands.
#pragma once

#include <cstddef>
#include <cstdio>
#include <string>
#include <string_view>

namespace vivv {

// The length of the well-formed UTF-8 sequence (RFC 3629: no overlong forms, no surrogates,
// nothing above U+10FFFF) starting at text[at], or 0 when the bytes there are not one.
inline std::size_t utf8_sequence_length(std::string_view text, std::size_t at) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
  const unsigned char lead = byte(at);
  if (lead < 0x80) return 1;
  std::size_t length = 0;
  unsigned char low = 0x80, high = 0xBF;  // the allowed range of the second byte
  if (lead >= 0xC2 && lead <= 0xDF) length = 2;
  else if (lead == 0xE0) length = 3, low = 0xA0;
  else if (lead >= 0xE1 && lead <= 0xEC) length = 3;
  else if (lead == 0xED) length = 3, high = 0x9F;  // not the surrogates D800–DFFF
  else if (lead >= 0xEE && lead <= 0xEF) length = 3;
  else if (lead == 0xF0) length = 4, low = 0x90;
  else if (lead >= 0xF1 && lead <= 0xF3) length = 4;
  else if (lead == 0xF4) length = 4, high = 0x8F;  // not above U+10FFFF
  else return 0;
  if (at + length > text.size()) return 0;
  if (byte(at + 1) < low || byte(at + 1) > high) return 0;
  for (std::size_t k = 2; k < length; ++k)
    if (byte(at + k) < 0x80 || byte(at + k) > 0xBF) return 0;
  return length;
}

// The characters of UTF-8 `text`: its bytes but the continuation bytes (10xxxxxx).
inline std::size_t utf8_characters(std::string_view text) {
  std::size_t count = 0;
  for (const char c : text) count += (static_cast<unsigned char>(c) & 0xC0) != 0x80;
  return count;
}

// `text` with every byte that does not belong to a well-formed UTF-8 character replaced by
// U+FFFD; valid text comes back unchanged.
inline std::string repaired_utf8(std::string_view text) {
  std::string repaired;
  repaired.reserve(text.size());
  for (std::size_t at = 0; at < text.size();) {
    const std::size_t length = utf8_sequence_length(text, at);
    if (length == 0) {
      repaired += "\xEF\xBF\xBD";
      ++at;
    } else {
      repaired.append(text.substr(at, length));
      at += length;
    }
  }
  return repaired;
}

// The longest prefix of `text` of at most `at_most` bytes that does not end inside a UTF-8
// character (a continuation byte 10xxxxxx never starts one).
inline std::string_view cut_at_character(std::string_view text, std::size_t at_most) {
  if (text.size() <= at_most) return text;
  std::size_t end = at_most;
  while (end > 0 && (static_cast<unsigned char>(text[end]) & 0xC0) == 0x80) --end;
  return text.substr(0, end);
}

// `text` in at most `at_most` bytes: all of it, or its beginning and its end with
// " … (N bytes left out) … " between them, each cut at a character boundary. The end of a
// program's standard error — the exception's line — says why it failed; a cut that kept only the
// beginning dropped exactly that.
inline std::string cut_in_the_middle(std::string_view text, std::size_t at_most) {
  if (text.size() <= at_most) return std::string(text);
  const std::size_t marker = 48;  // the longest " … (N bytes left out) … "
  const std::size_t budget = at_most > marker ? (at_most - marker) / 2 : 0;
  const std::string_view head = cut_at_character(text, budget);
  std::size_t start = text.size() - budget;
  while (start < text.size() && (static_cast<unsigned char>(text[start]) & 0xC0) == 0x80) ++start;
  const std::string_view tail = text.substr(start);
  return std::string(head) + " … (" + std::to_string(text.size() - head.size() - tail.size()) +
         " bytes left out) … " + std::string(tail);
}

// `text` cut to at most `at_most` bytes at a character boundary, with "… (N characters)" when
// it was longer, and repaired to UTF-8: how a program's text is quoted in a message.
inline std::string quoted_text(std::string_view text, std::size_t at_most = 300) {
  if (text.size() <= at_most) return repaired_utf8(text);
  return repaired_utf8(cut_at_character(text, at_most)) + "… (" + std::to_string(text.size()) +
         " characters)";
}

// `text` repaired to UTF-8, with the control characters (C0 but the newline, DEL, and C1 —
// which start terminal escape sequences) written as \x1b, \u0085 …: what may be printed to a
// terminal.
inline std::string terminal_safe(std::string_view text) {
  const std::string repaired = repaired_utf8(text);
  std::string safe;
  safe.reserve(repaired.size());
  char escape[8];
  for (std::size_t at = 0; at < repaired.size(); ++at) {
    const auto byte = static_cast<unsigned char>(repaired[at]);
    if ((byte < 0x20 && byte != '\n') || byte == 0x7F) {
      std::snprintf(escape, sizeof escape, "\\x%02x", byte);
      safe += escape;
    } else if (byte == 0xC2 && at + 1 < repaired.size() &&
               static_cast<unsigned char>(repaired[at + 1]) <= 0x9F) {  // U+0080–U+009F
      std::snprintf(escape, sizeof escape, "\\u%04x",
                    static_cast<unsigned char>(repaired[at + 1]));
      safe += escape;
      ++at;
    } else {
      safe += repaired[at];
    }
  }
  return safe;
}

}  // namespace vivv
