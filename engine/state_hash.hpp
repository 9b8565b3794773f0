// A 64-bit fingerprint of the dynamic state, for determinism tests: two runs agree
// bit for bit iff (barring a 2^-64 collision) their hashes agree.
#pragma once

#include <cstdint>

#include "engine/body_store.hpp"
#include "engine/contact_list.hpp"

namespace ballast {

std::uint64_t state_hash(const BodyStore& bodies, const ContactList& ball_contacts,
                         const ContactList& wall_contacts);

}  // namespace ballast
