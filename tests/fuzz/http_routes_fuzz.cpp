// libFuzzer target: the tuning page server's requests in memory (http_routes_entry.hpp).
#include "tests/fuzz/fuzz_main.hpp"
#include "tests/fuzz/http_routes_entry.hpp"
TNV_FUZZ_TARGET(tnv::fuzz::http_routes)
