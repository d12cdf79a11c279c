// A stand-in for libavutil.so.57 that no longer fits libsumocpp.so: it carries the soname and
// the symbol version, but none of the symbols libsumocpp.so takes from the real library (as a
// stand-in written for an older SUMO would lack a newer one's). The program must notice when
// it loads the libsumo module and load the real libraries instead (e2e LibsumoModuleCli).
extern "C" int orch_stale_stand_in() { return 0; }
