// A shared object in the plugin folder that is no HullInspect plugin (no
// HULLINSPECT_PLUGIN line): refused by its missing tag, never loaded.
extern "C" __attribute__((visibility("default"))) int some_library_function() { return 42; }
