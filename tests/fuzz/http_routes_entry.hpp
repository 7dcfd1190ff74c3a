#pragma once
// The tuning page server's requests, built in memory (no socket) and fed
// through its gate and routes (TuningServer::handle) on the emulated node
// whose node thread is not running: every job for the node is refused at
// once (503), so an input costs microseconds and the checks before the
// node are what is fuzzed. Built only with cpp-httplib (tnv_serve).
//
// Input: byte 0 = Host (bits 0-2: own, localhost, [::1], attacker.example,
// none, the fuzzed text), Origin (bits 3-5: the Host's, foreign, "null",
// none, the fuzzed text), credentials (bits 6-7: the bearer secret, the
// session cookie, a wrong bearer, none); byte 1 = route (bits 0-4, table
// in the entry; 20-23 take the fuzzed text as path or method, 24-27 are
// the Program panel's /api/program, preview, run and resume),
// Content-Type (bits 5-6: JSON, JSON with charset, text/plain, the fuzzed
// text), tab token (bit 7: a valid one, the fuzzed text); then the fuzzed
// text up to the first '\n', and the body after it.
//
// Invariants: the status is an HTTP status; a request the gate refused
// and every 4xx answer leave the state (control, jobs offered to the node
// thread) unchanged; a foreign Host is 403 whatever else the request
// carries; without credentials no API route answers 2xx; a JSON error
// answer names its reason.
#include <cstddef>
#include <cstdint>
#include <string>

namespace tnv::fuzz {

std::string http_routes(const std::uint8_t* data, std::size_t size);

}  // namespace tnv::fuzz
