/* SPDX-License-Identifier: BSD-2-Clause */
/* The device application against a scripted host: every byte the link
 * delivers is heard, however the bytes are cut into reads (several frames
 * in one read, or one byte at a time), and a job the device cannot take is
 * answered with an ERROR frame that carries the device's limits. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

/* the application itself, with its static state, in this test */
#include "../../firmware/app/app.c"

#define SPECTRA 4u
#define BANDS 8u

static uint8_t to_device[8192];
static size_t to_len, to_pos, read_size;
static unsigned idle_reads;
/* the bytes from later_at on arrive only after later_after idle reads (a
 * host that comes back); 0: all at once */
static size_t later_at;
static unsigned later_after;
static uint64_t now;
static jmp_buf hung;

static bw_frame_rx_t host_rx;
static bw_frame_t sent[64];
static unsigned n_sent;

static uint64_t t_counter(void) { return now += 100000000u; /* 0.1 G instructions a call */ }

static int t_link_read(uint8_t *b, size_t cap)
{
    size_t end = later_at && idle_reads < later_after ? later_at : to_len;
    if (to_pos == end) {
        if (++idle_reads > 100000u)
            longjmp(hung, 1); /* waiting for bytes that were already delivered */
        return 0;
    }
    size_t n = end - to_pos;
    if (n > read_size)
        n = read_size;
    if (n > cap)
        n = cap;
    memcpy(b, to_device + to_pos, n);
    to_pos += n;
    return (int)n;
}

static int t_link_write(const uint8_t *b, size_t len)
{
    for (size_t i = 0; i < len; i++)
        if (bw_frame_rx_byte(&host_rx, b[i], &sent[n_sent]) && n_sent < 63u)
            n_sent++;
    return (int)len;
}

static size_t sensor_pos;
static int t_sensor_open(const char *source)
{
    sensor_pos = 0;
    return strcmp(source, "scripted") ? -1 : 0;
}

static int t_sensor_read(int32_t *s, size_t cap)
{
    size_t n = 0;
    while (n < cap && sensor_pos < SPECTRA * BANDS) {
        s[n++] = (int32_t)((sensor_pos * 37u) % 1000u);
        sensor_pos++;
    }
    return (int)n;
}

static const bw_hal_t hal = {
    .counter = t_counter,
    .link_write = t_link_write,
    .link_read = t_link_read,
    .sensor_open = t_sensor_open,
    .sensor_read = t_sensor_read,
};

static void host_sends(uint8_t type, const uint8_t *d, uint16_t len)
{
    to_len += bw_frame_pack(to_device + to_len, type, 0, d, len);
}

static void script(uint32_t n_in)
{
    memset(sent, 0, sizeof sent);
    n_sent = 0;
    to_len = to_pos = later_at = 0;
    idle_reads = later_after = 0;
    bw_frame_rx_init(&host_rx);
    bw_job_t job;
    memset(&job, 0, sizeof job);
    job.shape = BW_SHAPE_SPECTRA;
    job.n_in = n_in;
    job.bands = BANDS;
    job.mode = BW_MODE_LOSSLESS;
    job.basis = BW_BASIS_HAAR;
    strcpy(job.source, "scripted");
    uint8_t jb[BW_JOB_SIZE];
    bw_job_pack(&job, jb);
    host_sends(BW_FT_JOB, jb, BW_JOB_SIZE);
}

static unsigned count_sent(uint8_t type)
{
    unsigned k = 0;
    for (unsigned i = 0; i < n_sent; i++)
        k += sent[i].type == type;
    return k;
}

/* JOB, ACK of the payload to come and QUIT, delivered in reads of `size`
 * bytes: the device encodes, sends the payload once, takes the ACK and
 * stops on QUIT. */
static void run_acked_job(size_t size)
{
    script(SPECTRA);
    uint8_t id[4];
    bw_put_u32(id, 1); /* the first payload of a boot */
    host_sends(BW_FT_ACK, id, 4);
    host_sends(BW_FT_QUIT, NULL, 0);
    read_size = size;
    if (setjmp(hung))
        fail_msg("the device waited for frames it had already read (%u frames sent)", n_sent);
    assert_int_equal(bw_app_run(&hal), 0);
    assert_int_equal(count_sent(BW_FT_START), 1); /* the ACK was heard: no second send */
    assert_int_equal(count_sent(BW_FT_END), 1);
    assert_int_equal(count_sent(BW_FT_ERROR), 0);
    assert_int_equal(to_pos, to_len);
}

static void frames_that_arrive_in_one_read_are_all_heard(void **state)
{
    (void)state;
    run_acked_job(sizeof to_device);
}

static void frames_that_arrive_a_byte_at_a_time_are_all_heard(void **state)
{
    (void)state;
    run_acked_job(1);
}

static void frames_cut_at_any_point_are_all_heard(void **state)
{
    (void)state;
    for (size_t size = 2; size < 200; size += 7)
        run_acked_job(size);
}

static void a_job_too_large_is_answered_with_the_device_limits(void **state)
{
    (void)state;
    script(APP_MAX_SAMPLES / BANDS + 1u);
    host_sends(BW_FT_QUIT, NULL, 0);
    read_size = sizeof to_device;
    if (setjmp(hung))
        fail_msg("the device did not stop on QUIT after an error");
    assert_int_equal(bw_app_run(&hal), 0);
    assert_int_equal(count_sent(BW_FT_ERROR), 1);
    assert_int_equal(count_sent(BW_FT_START), 0);
    int32_t st;
    bw_limits_t lim;
    assert_int_equal(sent[0].type, BW_FT_ERROR);
    assert_int_equal(sent[0].len, BW_ERROR_SIZE);
    assert_true(bw_error_unpack(sent[0].data, sent[0].len, &st, &lim));
    assert_int_equal(st, BW_ERR_WORK);
    assert_int_equal(lim.max_samples, APP_MAX_SAMPLES);
    assert_int_equal(lim.max_bands, APP_MAX_BANDS);
    assert_int_equal(lim.stream_bands, APP_STREAM_BANDS);
    assert_int_equal(lim.stream_level, APP_STREAM_LEVEL);
    assert_int_equal(lim.payload_cap, APP_PAYLOAD_CAP);
    /* a status alone (an older device) leaves the limits unsaid */
    assert_true(bw_error_unpack(sent[0].data, 4, &st, &lim));
    assert_int_equal(st, BW_ERR_WORK);
    assert_int_equal(lim.max_samples, 0);
    assert_false(bw_error_unpack(sent[0].data, 3, &st, &lim));
}

/* A job whose extension records (1403 bytes) come partly in a JOB_EXT frame
 * and partly after the JOB's fixed part: the payload carries them whole. */
static void extension_records_in_job_ext_frames_reach_the_payload(void **state)
{
    (void)state;
    static uint8_t area[1403];
    area[0] = BW_EXT_METADATA;
    area[1] = 0x80 | (1400 & 0x7F);
    area[2] = 1400 >> 7;
    for (size_t i = 3; i < sizeof area; i++)
        area[i] = (uint8_t)(i * 13 + 5);
    memset(sent, 0, sizeof sent);
    n_sent = 0;
    to_len = to_pos = later_at = 0;
    idle_reads = later_after = 0;
    sensor_pos = 0;
    bw_frame_rx_init(&host_rx);
    host_sends(BW_FT_JOB_EXT, area, 1000);
    bw_job_t job;
    memset(&job, 0, sizeof job);
    job.shape = BW_SHAPE_SPECTRA;
    job.n_in = SPECTRA;
    job.bands = BANDS;
    job.mode = BW_MODE_LOSSLESS;
    job.basis = BW_BASIS_HAAR;
    strcpy(job.source, "scripted");
    job.ext = area + 1000;
    job.ext_len = sizeof area - 1000;
    uint8_t jb[BW_FRAME_MAX_DATA];
    host_sends(BW_FT_JOB, jb, (uint16_t)bw_job_pack(&job, jb));
    uint8_t id[4];
    bw_put_u32(id, 1);
    host_sends(BW_FT_ACK, id, 4);
    host_sends(BW_FT_QUIT, NULL, 0);
    read_size = sizeof to_device;
    if (setjmp(hung))
        fail_msg("the device did not finish the job");
    assert_int_equal(bw_app_run(&hal), 0);
    assert_int_equal(count_sent(BW_FT_ERROR), 0);
    assert_int_equal(count_sent(BW_FT_START), 1);
    static uint8_t p[64 * BW_FRAME_MAX_DATA];
    size_t n = 0;
    for (unsigned i = 0; i < n_sent; i++)
        if (sent[i].type == BW_FT_DATA) {
            memcpy(p + n, sent[i].data, sent[i].len);
            n += sent[i].len;
        }
    bw_header_t h;
    assert_int_equal(bw_header_read(p, n, &h), BW_OK);
    assert_int_equal(h.version, 7);
    assert_int_equal(h.ext_len, sizeof area);
    assert_memory_equal(p + h.ext_off, area, sizeof area);

    /* more than the device holds: refused with BW_ERR_ARG, and the next
     * job starts afresh */
    memset(sent, 0, sizeof sent);
    n_sent = 0;
    to_len = to_pos = 0;
    bw_frame_rx_init(&host_rx);
    for (unsigned k = 0; k * 1000u <= APP_EXT_MAX; k++)
        host_sends(BW_FT_JOB_EXT, area, 1000);
    job.ext = NULL;
    job.ext_len = 0;
    host_sends(BW_FT_JOB, jb, (uint16_t)bw_job_pack(&job, jb));
    host_sends(BW_FT_QUIT, NULL, 0);
    if (setjmp(hung))
        fail_msg("the device did not stop after refusing the job");
    assert_int_equal(bw_app_run(&hal), 0);
    assert_int_equal(count_sent(BW_FT_ERROR), 1);
    int32_t st;
    bw_limits_t lim;
    assert_true(bw_error_unpack(sent[0].data, sent[0].len, &st, &lim));
    assert_int_equal(st, BW_ERR_ARG);
}

static void hello_is_answered_with_the_link_version_and_the_limits(void **state)
{
    (void)state;
    script(SPECTRA);
    to_len = 0; /* no job: HELLO, then QUIT */
    host_sends(BW_FT_HELLO, NULL, 0);
    host_sends(BW_FT_QUIT, NULL, 0);
    read_size = sizeof to_device;
    if (setjmp(hung))
        fail_msg("the device did not stop on QUIT after HELLO");
    assert_int_equal(bw_app_run(&hal), 0);
    assert_int_equal(n_sent, 1);
    assert_int_equal(sent[0].type, BW_FT_HELLO);
    uint8_t version;
    bw_limits_t lim;
    assert_true(bw_hello_unpack(sent[0].data, sent[0].len, &version, &lim));
    assert_int_equal(version, BW_LINK_VERSION);
    assert_int_equal(lim.max_samples, APP_MAX_SAMPLES);
    assert_int_equal(lim.stream_level, APP_STREAM_LEVEL);
    /* the host's rule and the device's agree: this job is too large to hold,
     * and streamed it fits */
    bw_dims_t d;
    bw_params_t p;
    bool streamed;
    memset(&p, 0, sizeof p);
    assert_int_equal(bw_dims_make(&d, BW_SHAPE_BRDF_ISO, 4, 0, 256, 1), BW_OK);
    assert_int_equal(bw_limits_admit(&lim, &d, &p, &streamed), BW_ERR_WORK);
    p.flags = BW_FLAG_STREAM_ORDER;
    p.basis = BW_BASIS_HAAR;
    assert_int_equal(bw_limits_admit(&lim, &d, &p, &streamed), BW_OK);
    assert_true(streamed);
}

/* A payload the host never acknowledges is sent MAX_SENDS times; the device
 * then keeps it, and a host that comes back later gets the chunks it asks
 * for (the whole payload for a bare RESEND) until its ACK releases it. */
static void a_kept_payload_is_resent_when_the_host_comes_back(void **state)
{
    (void)state;
    script(SPECTRA);
    later_at = to_len; /* JOB now; the rest after the device has given up */
    later_after = 5000u;
    uint8_t d[6], other[4];
    bw_put_u32(d, 1);
    bw_put_u16(d + 4, 0);
    bw_put_u32(other, 2);
    host_sends(BW_FT_RESEND, other, 4); /* a payload it does not hold: no answer */
    host_sends(BW_FT_RESEND, d, 6);     /* chunk 0 */
    host_sends(BW_FT_RESEND, d, 4);     /* all of it */
    host_sends(BW_FT_ACK, d, 4);
    host_sends(BW_FT_RESEND, d, 6); /* released: no answer */
    host_sends(BW_FT_QUIT, NULL, 0);
    read_size = sizeof to_device;
    if (setjmp(hung))
        fail_msg("the device hung (%u frames sent)", n_sent);
    assert_int_equal(bw_app_run(&hal), 0);
    assert_true(idle_reads >= later_after); /* it waited for the host */
    assert_int_equal(count_sent(BW_FT_START), MAX_SENDS + 1u);
    assert_int_equal(count_sent(BW_FT_DATA), MAX_SENDS + 2u);
    assert_int_equal(count_sent(BW_FT_END), MAX_SENDS + 2u);
    assert_int_equal(to_pos, to_len);
    /* the chunk asked for alone is the payload's chunk 0, as first sent */
    const bw_frame_t *first = NULL, *alone = NULL;
    for (unsigned i = 0; i < n_sent; i++)
        if (sent[i].type == BW_FT_DATA) {
            if (!first)
                first = &sent[i];
            if (i && sent[i - 1u].type == BW_FT_END)
                alone = &sent[i];
        }
    assert_non_null(alone);
    assert_int_equal(alone->len, first->len);
    assert_memory_equal(alone->data, first->data, first->len);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(frames_that_arrive_in_one_read_are_all_heard),
        cmocka_unit_test(frames_that_arrive_a_byte_at_a_time_are_all_heard),
        cmocka_unit_test(frames_cut_at_any_point_are_all_heard),
        cmocka_unit_test(a_job_too_large_is_answered_with_the_device_limits),
        cmocka_unit_test(hello_is_answered_with_the_link_version_and_the_limits),
        cmocka_unit_test(extension_records_in_job_ext_frames_reach_the_payload),
        cmocka_unit_test(a_kept_payload_is_resent_when_the_host_comes_back),
    };
    return cmocka_run_group_tests_name("app", tests, NULL, NULL);
}
