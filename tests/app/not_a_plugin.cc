// A shared library with no plugin registration in it: named in `Additional
// shared libraries`, it must be refused with one clear message.
extern "C" int
estep_test_not_a_plugin()
{
  return 42;
}
