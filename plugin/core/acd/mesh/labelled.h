// A row of a table of choices: an enum's value, the label scripts and menus use, and its help.
#pragma once

namespace acd {

template <class E> struct Labelled
{
	E           id;
	const char* label;
	const char* help;
};

} // namespace acd
