#pragma once
// The model-file reference of the contact laws, made from their own parameter specs (ParamSpec),
// so a law's key cannot lack its documentation: `vorodec laws` prints it, docs/model-file.md holds
// it, and a test checks that the two agree.
#include <string>

#include "vorodec/laws/contact_law.hpp"

namespace vorodec::laws {

// A key's valid range as messages and the reference state it: "> 0 Pa/m", ">= 0 and <= 90 deg".
std::string range_text(const ParamSpec& spec);

// Markdown: one section per law of the registry with its key table.
std::string law_reference();

}  // namespace vorodec::laws
