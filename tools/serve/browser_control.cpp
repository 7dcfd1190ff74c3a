#include "tools/serve/browser_control.hpp"

#include <algorithm>

namespace tnv::serve {

bool BrowserControl::valid_token(const std::string& token) {
  if (token.size() < 8 || token.size() > 64) return false;
  return std::all_of(token.begin(), token.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '-' || c == '_';
  });
}

bool BrowserControl::expired(Clock::time_point now) const {
  return holder_.empty() || holder_gone_ || now - holder_seen_ > deadman_;
}

std::string BrowserControl::take(const std::string& token, Clock::time_point now) {
  if (!valid_token(token)) return "no valid browser token (reload the page)";
  const std::lock_guard lock(mutex_);
  if (holder_ != token && !expired(now)) return kAnotherBrowserHasControl;
  holder_ = token;
  holder_seen_ = now;
  holder_gone_ = false;
  return "";
}

bool BrowserControl::release(const std::string& token) {
  const std::lock_guard lock(mutex_);
  if (holder_.empty() || holder_ != token) return false;
  holder_.clear();
  return true;
}

bool BrowserControl::seen(const std::string& token, Clock::time_point now) {
  const std::lock_guard lock(mutex_);
  if (holder_.empty() || holder_ != token || expired(now)) return false;
  holder_seen_ = now;
  return true;
}

void BrowserControl::gone(const std::string& token) {
  const std::lock_guard lock(mutex_);
  if (!holder_.empty() && holder_ == token) holder_gone_ = true;
}

std::string BrowserControl::lapse(Clock::time_point now) {
  const std::lock_guard lock(mutex_);
  if (holder_.empty() || !expired(now)) return "";
  std::string gone;
  gone.swap(holder_);
  return gone;
}

std::string BrowserControl::check(const std::string& token, Clock::time_point now) {
  const std::lock_guard lock(mutex_);
  if (!holder_.empty() && holder_ == token && !expired(now)) {
    holder_seen_ = now;
    return "";
  }
  if (!expired(now)) return kAnotherBrowserHasControl;
  return "take control first (the \"Take control\" button)";
}

bool BrowserControl::holds(const std::string& token, Clock::time_point now) {
  const std::lock_guard lock(mutex_);
  return !holder_.empty() && holder_ == token && !expired(now);
}

bool BrowserControl::anyone_holds(Clock::time_point now) {
  const std::lock_guard lock(mutex_);
  return !expired(now);
}

}  // namespace tnv::serve
