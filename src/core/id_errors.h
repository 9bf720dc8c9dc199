#pragma once

// What a world's calls say of an id that names nothing (sphys/slot_id.h): the null id, or one
// whose object was removed or never added. One wording for bodies, joints and robots.

#include <cstdint>
#include <string>
#include <string_view>

#include "sphys/error.h"
#include "sphys/slot_id.h"

namespace sphys {

// An id as errors write it: its slot and generation, "3.1".
template <class Tag>
std::string id_text(SlotId<Tag> id) {
  return std::to_string(id.index) + "." + std::to_string(id.generation);
}

// "no body with id 3.1 in the world (removed, or never added)", for `kind` "body".
template <class Tag>
std::string not_in_world(std::string_view kind, SlotId<Tag> id) {
  return "no " + std::string(kind) + " with id " + id_text(id) +
         " in the world (removed, or never added)";
}

// The slot `id` names, for a call given it; throws sphys::Error for the null id (naming its
// `type`, "BodyId") and for an id the world holds no `kind` of (`alive` false).
template <class Tag>
std::uint32_t slot_named(SlotId<Tag> id, bool alive, std::string_view kind, std::string_view type) {
  if (id.is_null()) {
    throw Error("the null " + std::string(kind) + " id (" + std::string(type) + "{}) names no " +
                std::string(kind));
  }
  if (!alive) throw Error(not_in_world(kind, id));
  return id.index;
}

}  // namespace sphys
