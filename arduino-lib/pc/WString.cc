// SPDX-License-Identifier: MIT
// Arduino's String for the PC core: what does not fit in its header.
#include "WString.h"

#include "Arduino.h"

std::string String::Unsigned(uint32_t n, unsigned char base) {
  if (base < 2 || base > 36) base = 10;
  std::string digits;
  do {
    const int d = static_cast<int>(n % base);
    digits.insert(digits.begin(), static_cast<char>(d < 10 ? '0' + d : 'a' + d - 10));
    n /= base;
  } while (n != 0);
  return digits;
}

std::string String::Signed(int32_t n, unsigned char base) {
  if (base != 10 || n >= 0) return Unsigned(static_cast<uint32_t>(n), base);
  return "-" + Unsigned(0U - static_cast<uint32_t>(n), 10);
}

String::String(double x, unsigned char decimals) {
  // as the board's dtostrf with a width of decimals + 2, into a string as long as it takes
  const int width = decimals + 2;
  const int size = snprintf(nullptr, 0, "%*.*f", width, decimals, x);
  text_.resize(static_cast<size_t>(size > 0 ? size : 0));
  snprintf(text_.data(), text_.size() + 1, "%*.*f", width, decimals, x);
}

bool String::equalsIgnoreCase(const String& s) const {
  if (s.text_.size() != text_.size()) return false;
  for (size_t i = 0; i < text_.size(); ++i) {
    if (tolower(static_cast<unsigned char>(text_[i])) !=
        tolower(static_cast<unsigned char>(s.text_[i]))) {
      return false;
    }
  }
  return true;
}

String String::substring(unsigned int from, unsigned int to) const {
  if (from > to) {
    const unsigned int swap = from;
    from = to;
    to = swap;
  }
  if (from >= text_.size()) return String();
  if (to > text_.size()) to = static_cast<unsigned int>(text_.size());
  return String(text_.substr(from, to - from).c_str());
}

void String::replace(const String& what, const String& with) {
  if (what.text_.empty()) return;
  for (size_t at = text_.find(what.text_); at != std::string::npos;
       at = text_.find(what.text_, at + with.text_.size())) {
    text_.replace(at, what.text_.size(), with.text_);
  }
}

void String::trim() {
  const size_t first = text_.find_first_not_of(" \t\n\v\f\r");
  if (first == std::string::npos) {
    text_.clear();
    return;
  }
  text_ = text_.substr(first, text_.find_last_not_of(" \t\n\v\f\r") - first + 1);
}
