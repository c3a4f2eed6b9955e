// doctest's runner (select cases with -tc="name", list them with -ltc).
#define DOCTEST_CONFIG_IMPLEMENT_WITH_MAIN
#include <doctest/doctest.h>
