// SPDX-License-Identifier: MIT
// Arduino's String for the PC core: the board's text class, with the same conversions (numbers
// as the board writes them: 32-bit integers, floats with two decimals unless told).
#ifndef UNIMOUSE_PC_WSTRING_H_
#define UNIMOUSE_PC_WSTRING_H_

#include <ctype.h>
#include <stdint.h>
#include <stdlib.h>

#include <string>

class String {
 public:
  String(const char* text = "") : text_(text != nullptr ? text : "") {}
  explicit String(char c) : text_(1, c) {}
  explicit String(unsigned char n, unsigned char base = 10) : text_(Unsigned(n, base)) {}
  explicit String(int n, unsigned char base = 10) : text_(Signed(n, base)) {}
  explicit String(unsigned int n, unsigned char base = 10) : text_(Unsigned(n, base)) {}
  explicit String(long n, unsigned char base = 10) : text_(Signed(int32_t(n), base)) {}
  explicit String(unsigned long n, unsigned char base = 10) : text_(Unsigned(uint32_t(n), base)) {}
  explicit String(float x, unsigned char decimals = 2) : String(double(x), decimals) {}
  explicit String(double x, unsigned char decimals = 2);

  const char* c_str() const { return text_.c_str(); }
  unsigned int length() const { return static_cast<unsigned int>(text_.size()); }
  bool isEmpty() const { return text_.empty(); }
  bool reserve(unsigned int size) {
    text_.reserve(size);
    return true;
  }

  char charAt(unsigned int i) const { return i < text_.size() ? text_[i] : 0; }
  char operator[](unsigned int i) const { return charAt(i); }
  char& operator[](unsigned int i) {
    static char nothing;
    nothing = 0;
    return i < text_.size() ? text_[i] : nothing;
  }
  void setCharAt(unsigned int i, char c) {
    if (i < text_.size()) text_[i] = c;
  }
  void toCharArray(char* buffer, unsigned int size, unsigned int from = 0) const {
    getBytes(reinterpret_cast<unsigned char*>(buffer), size, from);
  }
  void getBytes(unsigned char* buffer, unsigned int size, unsigned int from = 0) const {
    if (size == 0) return;
    unsigned int n = 0;
    for (; n + 1 < size && from + n < text_.size(); ++n) buffer[n] = text_[from + n];
    buffer[n] = 0;
  }

  template <typename T>
  bool concat(const T& value) {
    text_ += String(value).text_;
    return true;
  }
  bool concat(const String& s) {
    text_ += s.text_;
    return true;
  }
  bool concat(const char* s) {
    if (s != nullptr) text_ += s;
    return true;
  }
  bool concat(char c) {
    text_ += c;
    return true;
  }
  template <typename T>
  String& operator+=(const T& value) {
    concat(value);
    return *this;
  }

  int compareTo(const String& s) const { return text_.compare(s.text_); }
  bool equals(const String& s) const { return text_ == s.text_; }
  bool equalsIgnoreCase(const String& s) const;
  bool operator==(const String& s) const { return equals(s); }
  bool operator==(const char* s) const { return text_ == (s != nullptr ? s : ""); }
  bool operator!=(const String& s) const { return !equals(s); }
  bool operator!=(const char* s) const { return !(*this == s); }
  bool operator<(const String& s) const { return compareTo(s) < 0; }
  bool operator>(const String& s) const { return compareTo(s) > 0; }
  bool startsWith(const String& s) const { return text_.compare(0, s.text_.size(), s.text_) == 0; }
  bool endsWith(const String& s) const {
    return s.text_.size() <= text_.size() &&
           text_.compare(text_.size() - s.text_.size(), s.text_.size(), s.text_) == 0;
  }

  int indexOf(char c, unsigned int from = 0) const { return Found(text_.find(c, from)); }
  int indexOf(const String& s, unsigned int from = 0) const {
    return Found(text_.find(s.text_, from));
  }
  int lastIndexOf(char c) const { return Found(text_.rfind(c)); }
  int lastIndexOf(const String& s) const { return Found(text_.rfind(s.text_)); }
  String substring(unsigned int from) const { return substring(from, length()); }
  String substring(unsigned int from, unsigned int to) const;

  void replace(const String& what, const String& with);
  void replace(char what, char with) {
    for (char& c : text_) {
      if (c == what) c = with;
    }
  }
  void remove(unsigned int from) { remove(from, length()); }
  void remove(unsigned int from, unsigned int count) {
    if (from < text_.size()) text_.erase(from, count);
  }
  void toLowerCase() {
    for (char& c : text_) c = static_cast<char>(tolower(static_cast<unsigned char>(c)));
  }
  void toUpperCase() {
    for (char& c : text_) c = static_cast<char>(toupper(static_cast<unsigned char>(c)));
  }
  void trim();

  /// The number the text starts with, as the board reads it: a 32-bit long, or 0.
  long toInt() const { return static_cast<int32_t>(atol(text_.c_str())); }
  float toFloat() const { return static_cast<float>(atof(text_.c_str())); }
  double toDouble() const { return atof(text_.c_str()); }

 private:
  // as the board's ltoa and ultoa write them: a sign in base 10 only
  static std::string Signed(int32_t n, unsigned char base);
  static std::string Unsigned(uint32_t n, unsigned char base);
  static int Found(size_t at) { return at == std::string::npos ? -1 : static_cast<int>(at); }
  std::string text_;
};

template <typename T>
String operator+(const String& a, const T& b) {
  String sum(a);
  sum.concat(b);
  return sum;
}
inline String operator+(const char* a, const String& b) {
  String sum(a);
  sum.concat(b);
  return sum;
}

#endif  // UNIMOUSE_PC_WSTRING_H_
