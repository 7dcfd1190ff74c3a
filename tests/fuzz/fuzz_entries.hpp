#pragma once
// The fuzzed entry points, shared by the libFuzzer targets (*_fuzz.cpp,
// built with -DTNV_FUZZ=ON and clang, scripts/fuzz.sh) and by the corpus
// regression test of the normal build (corpus_regression_test.cpp), which
// feeds every checked-in corpus file through the same function.
//
// Each returns "" when the input was handled and every invariant it can
// check held, else a one-line description of the broken invariant (the
// libFuzzer target aborts on it, so it counts as a crash).
#include <cstddef>
#include <cstdint>
#include <string>

namespace tnv::fuzz {

// Raw CAN frames and tick steps into the firmware node (frame_codec +
// CanNode::service on an in-memory port; one node for the whole run, reset
// in place between inputs), 12 bytes a frame: flags, id u16 LE, dlc, 8
// data bytes. Flags: bit 0 extended; bit 1 run ticks first, bits 2..4 how
// many (2^k, at most 64 in one input); bit 5 the id is message id (low 5
// bits of the id's first byte) to this node.
std::string can_frames(const std::uint8_t* data, std::size_t size);

// The frame codec alone: classify() and every field's read / write round
// trip, 12 bytes a frame as for can_frames (flags bit 0 extended).
std::string frame_codec(const std::uint8_t* data, std::size_t size);

// PARAM_REQUEST sequences (get / set / stage / commit / discard) against a
// model of the staged set, 6 bytes a request: op, parameter index (table
// order, or a raw id when bit 7 is set: that byte and the next), value u32 LE.
std::string param_set(const std::uint8_t* data, std::size_t size);

// A scenario TOML text through the parser, its validation and the fault
// timeline built from its [[fault]] tables.
std::string scenario_toml(const std::uint8_t* data, std::size_t size);

// Bytes as the stored parameter image(s), loaded through
// drivers::FileParamStorage and the two-generation loader. Byte 0: bit 0
// the rest is the current image only / split in half (current, previous),
// bit 1 re-seal the CRC (so mutations reach the value checks).
std::string param_image(const std::uint8_t* data, std::size_t size);

// Bytes as an RS274/NGC program through the LinuxCNC-dialect interpreter
// (tools/gcode/canon_interpreter.hpp) with a small tool table and offsets.
std::string gcode_canon(const std::uint8_t* data, std::size_t size);

}  // namespace tnv::fuzz
