#include "tools/serve/freq_response_for_page.hpp"

#include "tools/serve/api_error.hpp"

namespace tnv::serve {

FreqResponseRequest parse_freq_response_request(const nlohmann::json& body) {
  FreqResponseRequest r;
  if (!body.is_object() || !body.contains("axis") || !body["axis"].is_string())
    throw ApiError(kHttpBadRequest, "freq-response: give \"axis\": \"x\" or \"y\"");
  r.axis = body["axis"].get<std::string>();
  if (r.axis != "x" && r.axis != "y") throw ApiError(kHttpBadRequest, "freq-response: axis must be \"x\" or \"y\"");
  r.loop = body.value("loop", std::string("speed"));
  if (r.loop != "speed" && r.loop != "position")
    throw ApiError(kHttpBadRequest, "freq-response: loop must be \"speed\" or \"position\"");
  return r;
}

nlohmann::json freq_response_for_page(can_host::NodeClient& /*client*/, const FreqResponseRequest& /*request*/) {
  throw ApiError(kHttpNotImplemented, kFreqResponseMissing);
}

}  // namespace tnv::serve
