#include "report/stamp.hpp"

#include <openssl/evp.h>

#include <memory>
#include <stdexcept>

namespace glrc::report {

namespace {

constexpr size_t kDigits = 64;

std::string sha256_hex(std::string_view text) {
  std::unique_ptr<EVP_MD_CTX, decltype(&EVP_MD_CTX_free)> ctx(EVP_MD_CTX_new(), EVP_MD_CTX_free);
  unsigned char md[EVP_MAX_MD_SIZE];
  unsigned int length = 0;
  if (!ctx || EVP_DigestInit_ex(ctx.get(), EVP_sha256(), nullptr) != 1 ||
      EVP_DigestUpdate(ctx.get(), text.data(), text.size()) != 1 ||
      EVP_DigestFinal_ex(ctx.get(), md, &length) != 1)
    throw std::runtime_error("SHA-256 failed (OpenSSL)");
  static constexpr char kHex[] = "0123456789abcdef";
  std::string hex;
  for (unsigned int k = 0; k < length; ++k)
    hex += kHex[md[k] >> 4], hex += kHex[md[k] & 15];
  return hex;
}

}  // namespace

std::string stamp_placeholder() {
  return std::string(kStampPrefix) + std::string(kDigits, '0');
}

std::string stamped(std::string text) {
  const size_t at = text.find(stamp_placeholder());
  if (at == std::string::npos) throw std::logic_error("stamped: the text holds no placeholder");
  const std::string hex = sha256_hex(text);
  text.replace(at + kStampPrefix.size(), kDigits, hex);
  return text;
}

bool stamp_intact(std::string_view text) {
  const size_t at = text.find(kStampPrefix);
  if (at == std::string_view::npos || text.size() - at - kStampPrefix.size() < kDigits)
    return false;
  const std::string_view digits = text.substr(at + kStampPrefix.size(), kDigits);
  std::string zeroed(text);
  zeroed.replace(at + kStampPrefix.size(), kDigits, std::string(kDigits, '0'));
  return sha256_hex(zeroed) == digits;
}

std::string stamp_writer(std::string_view text) {
  const size_t at = text.find(kStampPrefix);
  if (at == std::string_view::npos || at == 0 || text[at - 1] != ' ') return {};
  const std::string_view before = text.substr(0, at - 1);
  const size_t space = before.rfind(' ');
  if (space == std::string_view::npos || !before.substr(0, space).ends_with("glrefcheck"))
    return {};
  return std::string(before.substr(space + 1));
}

std::string stamped_json(std::string_view writer, const std::string& json_text) {
  if (!json_text.starts_with("{\n"))
    throw std::logic_error("stamped_json: expected an object as dump(2) writes it");
  return stamped("{\n  \"written_by\": \"glrefcheck " + std::string(writer) + " " +
                 stamp_placeholder() + "\",\n" + json_text.substr(2));
}

JsonStamp json_stamp(bool has_written_by, std::string_view text) {
  if (!has_written_by) return JsonStamp::none;
  return stamp_intact(text) ? JsonStamp::intact : JsonStamp::edited;
}

std::string edited_stamp_message(std::string_view source) {
  return std::string(source) +
         ": written_by: expected the stamp glrefcheck wrote to match the file's text (remove the "
         "field to read the file as it stands), got a file edited since glrefcheck wrote it";
}

std::string content_digest(std::string_view text) {
  return "sha256:" + sha256_hex(text);
}

}  // namespace glrc::report
