/* Times Embree 3's BVH build (rtcCommitScene) of the triangles in a gen_big.py .tri dump.
 *
 *   gcc -O2 -o embree_build embree_build.c -lembree3
 *   ./embree_build FILE.tri high|medium|low [threads=2] [runs=3]
 *
 * One device ("threads=N"), a warm-up commit of one triangle (so thread start-up is not
 * timed), then `runs` times: new scene + TRIANGLE geometry over shared buffers, build quality
 * set on scene and geometry, rtcCommitScene timed with CLOCK_MONOTONIC, scene released.
 * Prints VmRSS before the first build, after it (scene alive), and VmHWM at the end.
 */
#include <embree3/rtcore.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static double now(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + ts.tv_nsec * 1e-9;
}

static long status_kb(const char *key) {
    FILE *f = fopen("/proc/self/status", "r");
    char line[256];
    long v = -1;
    size_t n = strlen(key);
    while (f && fgets(line, sizeof line, f))
        if (!strncmp(line, key, n)) { v = atol(line + n + 1); break; }
    if (f) fclose(f);
    return v;
}

static void check(RTCDevice d, const char *what) {
    enum RTCError e = rtcGetDeviceError(d);
    if (e != RTC_ERROR_NONE) { fprintf(stderr, "%s: embree error %d\n", what, (int)e); exit(1); }
}

static RTCScene make_scene(RTCDevice dev, enum RTCBuildQuality q, float *v, unsigned nv,
                           unsigned *t, unsigned nt) {
    RTCScene s = rtcNewScene(dev);
    rtcSetSceneBuildQuality(s, q);
    RTCGeometry g = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_TRIANGLE);
    rtcSetGeometryBuildQuality(g, q);
    rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, v, 0,
                               3 * sizeof(float), nv);
    rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, t, 0,
                               3 * sizeof(unsigned), nt);
    rtcCommitGeometry(g);
    rtcAttachGeometry(s, g);
    rtcReleaseGeometry(g);
    check(dev, "geometry");
    return s;
}

int main(int argc, char **argv) {
    if (argc < 3) { fprintf(stderr, "usage: %s FILE.tri high|medium|low [threads] [runs]\n", argv[0]); return 2; }
    const char *qname = argv[2];
    enum RTCBuildQuality q = !strcmp(qname, "high") ? RTC_BUILD_QUALITY_HIGH
                           : !strcmp(qname, "medium") ? RTC_BUILD_QUALITY_MEDIUM
                           : RTC_BUILD_QUALITY_LOW;
    int threads = argc > 3 ? atoi(argv[3]) : 2;
    int runs = argc > 4 ? atoi(argv[4]) : 3;

    FILE *f = fopen(argv[1], "rb");
    if (!f) { perror(argv[1]); return 1; }
    char magic[4];
    uint32_t nv, nt;
    if (fread(magic, 1, 4, f) != 4 || memcmp(magic, "TRI1", 4) || fread(&nv, 4, 1, f) != 1 ||
        fread(&nt, 4, 1, f) != 1) { fprintf(stderr, "bad header\n"); return 1; }
    /* Shared vertex buffers must be readable 16 bytes at a time past the last vertex: pad. */
    float *v = malloc((size_t)nv * 12 + 16);
    unsigned *t = malloc((size_t)nt * 12 + 16);
    if (fread(v, 12, nv, f) != nv || fread(t, 12, nt, f) != nt) { fprintf(stderr, "short file\n"); return 1; }
    fclose(f);

    char config[64];
    snprintf(config, sizeof config, "threads=%d", threads);
    RTCDevice dev = rtcNewDevice(config);
    if (!dev) { fprintf(stderr, "rtcNewDevice failed\n"); return 1; }

    /* Warm-up: one triangle, so the task system is up before timing. */
    float wv[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 0};
    unsigned wt[4] = {0, 1, 2, 0};
    RTCScene w = make_scene(dev, q, wv, 3, wt, 1);
    rtcCommitScene(w);
    rtcReleaseScene(w);

    long rss0 = status_kb("VmRSS:");
    printf("embree %ld quality=%s threads=%d triangles=%u vertices=%u input_rss_MB=%.1f\n",
           (long)rtcGetDeviceProperty(dev, RTC_DEVICE_PROPERTY_VERSION), qname, threads,
           nt, nv, rss0 / 1024.0);
    for (int r = 0; r < runs; r++) {
        RTCScene s = make_scene(dev, q, v, nv, t, nt);
        double t0 = now();
        rtcCommitScene(s);
        double dt = now() - t0;
        check(dev, "commit");
        long rss1 = status_kb("VmRSS:");
        struct RTCBounds b;
        rtcGetSceneBounds(s, &b);
        printf("run=%d build_ms=%.1f rss_after_MB=%.1f rss_delta_MB=%.1f bytes_per_tri=%.1f "
               "bounds=(%.2f %.2f %.2f)-(%.2f %.2f %.2f)\n",
               r, dt * 1e3, rss1 / 1024.0, (rss1 - rss0) / 1024.0,
               (rss1 - rss0) * 1024.0 / nt, b.lower_x, b.lower_y, b.lower_z, b.upper_x,
               b.upper_y, b.upper_z);
        fflush(stdout);
        rtcReleaseScene(s);
    }
    printf("VmHWM_MB=%.1f (peak, includes the %.1f MB input)\n", status_kb("VmHWM:") / 1024.0,
           rss0 / 1024.0);
    rtcReleaseDevice(dev);
    return 0;
}
