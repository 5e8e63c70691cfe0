#include "toolio/sm_object_flags.hpp"

#include <fmt/format.h>

namespace sm::tools {

std::vector<std::string> object_flag_lines(uint32_t header, const HwConfig& hw, const Regs& regs) {
  std::vector<std::string> out;
  if (header & 0x200u)
    out.push_back(fmt::format(
        "TABLE-FULL: a pixel found all LABEL_SLOTS = {} labels in use and was dropped as background, so an "
        "object may be missing or cut short. Labels are held by components open on the last two rows and by "
        "finished ones of at least OBJ_MIN_PIXELS = {} pixels: raise OBJ_NEAR (now {}) or OBJ_MIN_PIXELS to "
        "leave out small components, or build with a larger LABEL_SLOTS.",
        hw.label_slots, regs.obj_min_pixels, regs.obj_near));
  if (header & 0x100u)
    out.push_back(fmt::format(
        "TOO-MANY: more than MAX_OBJECTS = {} components of at least OBJ_MIN_PIXELS = {} pixels; the first {} in "
        "label order are listed and the others dropped: raise OBJ_MIN_PIXELS or OBJ_NEAR (now {}), or build with "
        "a larger MAX_OBJECTS.",
        hw.max_objects, regs.obj_min_pixels, hw.max_objects, regs.obj_near));
  if (header & 0x400u)
    out.push_back(
        "LOST: the object packet of at least one earlier frame was dropped, because the object stream "
        "(m_axis_obj) was still sending the packet before it (tready low); those lists reached the register "
        "file only. Keep m_axis_obj_tready high, or read the list from the registers (OBJ_HEADER) each frame.");
  return out;
}

}  // namespace sm::tools
