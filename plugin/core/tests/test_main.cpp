#include "testing.h"

#include <exception>

namespace acdtest {
std::vector<Case>& registry()
{
	static std::vector<Case> r;
	return r;
}
int failures = 0;
} // namespace acdtest

int main(int argc, char** argv)
{
	int passed = 0, failed = 0;
	for (auto& c : acdtest::registry()) {
		if (argc > 1 && std::string(argv[1]) != c.name) continue;
		const int before = acdtest::failures;
		try {
			c.fn();
		}
		catch (const std::exception& e) {
			std::printf("  FAILED %s: exception %s\n", c.name, e.what());
			++acdtest::failures;
		}
		const bool ok = acdtest::failures == before;
		std::printf("%s %s\n", ok ? "[ OK ]" : "[FAIL]", c.name);
		(ok ? passed : failed)++;
	}
	std::printf("%d passed, %d failed\n", passed, failed);
	return failed == 0 ? 0 : 1;
}
