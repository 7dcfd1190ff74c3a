#include "tools/serve/freq_response_for_page.hpp"

#include "hal/axis_choice.hpp"
#include "tools/can/freq_response_json.hpp"
#include "tools/can/freq_response_run.hpp"
#include "tools/serve/api_error.hpp"

namespace tnv::serve {

FreqResponseRequest parse_freq_response_request(const nlohmann::json& body) {
  FreqResponseRequest r;
  if (!body.is_object() || !body.contains("axis") || !body["axis"].is_string())
    throw ApiError(kHttpBadRequest, "freq-response: give \"axis\": \"x\" or \"y\"");
  r.axis = body["axis"].get<std::string>();
  if (!hal::axis_from_name(r.axis))
    throw ApiError(kHttpBadRequest, "freq-response: axis must be " + std::string(hal::kQuotedAxisChoices));
  const nlohmann::json loop = body.value("loop", nlohmann::json("open"));
  if (!loop.is_string() || !tune::parse_loop_kind(loop.get<std::string>(), r.loop))
    throw ApiError(kHttpBadRequest, "freq-response: loop must be \"plant\", \"open\" or \"closed\"");
  return r;
}

nlohmann::json freq_response_for_page(can_host::NodeClient& client, const FreqResponseRequest& request) {
  can_host::FreqResponseOptions options;
  options.loop = request.loop;
  options.plant_model = request.plant_model;
  const hal::Axis axis = hal::axis_from_name(request.axis).value_or(hal::Axis::x);
  return can_host::freq_response_json(can_host::run_freq_response(client, axis, options));
}

}  // namespace tnv::serve
