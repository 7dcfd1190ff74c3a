#pragma once
// Parameters as a person reads and types them: "x.controller=rdvsc",
// "x.shaper.enable=on", "x.sliding.gamma=0.25". Parsing checks the value
// against the table (type, range, allowed set) before anything is sent.
#include <optional>
#include <string>
#include <vector>

#include "firmware/can/param_table.hpp"

namespace tnv::can_host {

namespace can = tnv::fw::can;

// The value as text: enum / boolean names where the table has them,
// integers without decimals, floats with up to 9 significant digits (a
// float32 prints back exactly).
std::string format_param_value(const can::ParamDef& p, double value);

// "0 .. 1", "{pid, dvsc, rdvsc}", "{125, 250, 500, 1000}".
std::string range_text(const can::ParamDef& p);

// A typed value: a number, or for enum/boolean parameters one of its names
// (booleans also take on/off, true/false, yes/no). nullopt with `error`
// naming the parameter and what is wrong; the value is range-checked with
// check_value() (read-only parameters are refused).
std::optional<double> parse_param_value(const can::ParamDef& p, const std::string& text, std::string& error);

// A parameter by name or by id ("x.sliding.gamma", "0x0116", "278").
const can::ParamDef* find_param_by_text(const std::string& name_or_id);

// The parameters a `params get` argument names, in table order: one by
// name or id, a shell-style glob ("x.*.gamma", "?.limits.*"), or a group
// by its dotted prefix ("x.sliding" or "x.sliding."). Empty when nothing
// matches.
std::vector<const can::ParamDef*> params_matching(const std::string& pattern);

// A parameter name close to `name` for "did you mean" messages ("" if none).
std::string closest_param_name(const std::string& name);

}  // namespace tnv::can_host
