/*
 * nmv_fixed.c: seed 000's moving-variance flight-mode detector (NMV, eq. 1-3, 7, 8) in integer
 * arithmetic, as a microcontroller runs it, speaking flightmode's detector pipe protocol
 * (docs/detector_pipe.md; flightmode/detector/pipe.py):
 *
 *   stdin:  one JSON header line {"fs_hz": .., "channels": [..], "units": {..}, "framing": "csv"|"f64",
 *           "params": {..}}, then per sample either one CSV line "t_s,<channels...>" (framing csv) or
 *           (1 + channels) little-endian IEEE-754 float64 values, t_s first (framing f64);
 *   stdout: per sample one line "0" or "1" (csv) or one byte 0x00 or 0x01 (f64); 1 = at rest, the
 *           radio may transmit.
 *
 * The same algorithm, bit for bit, as flightmode.detector.fixed_point (its docstring states it):
 *   count  c = clip(rint(a / lsb_g), -128, 127)        the LIS302DL's 8-bit output at +-2 g (18 mg/digit)
 *   sums   S1 = sum c, S2 = sum c^2 over the last N    seed 000 eq. 2-3 (add the new, drop the oldest)
 *   D      = N S2 - S1^2 = N^2 MV                      eq. 1 times N^2: no division
 *   static (eq. 7) when D 2^f < T N^2 on every axis, T = rint(k sigma^2 2^f) the threshold register
 *   final static (eq. 8) when the last ceil(T_th / W_s) checks (one every N samples) were static.
 * A time gap (more than 1.5 sample periods) resets the sums and the checks; each sample's answer is
 * the latest check's final static (0 before the first check).
 *
 * Parameters (header "params", all optional): window_s (1.0), k (4.0), time_threshold_s (4.0),
 * sigma2_counts (a number or three, counts^2; default 1/12, the quantisation floor) or, without it,
 * sigma2 (g^2, as the built-in nmv takes it; divided by lsb_g^2), lsb_g (0.018), frac_bits (8).
 * The signal path is integer only; floating point is used for the configuration (the register T)
 * and to emulate the sensor's ADC (g -> count), which the real part does in hardware.
 *
 * I/O: read(2)/write(2) with our own buffers; the answers are flushed before every read that may
 * block, so the program never sits on answers the harness waits for (the protocol's one rule).
 *
 * Build: cc -std=c99 -O2 -o nmv_fixed nmv_fixed.c -lm      (C99 + POSIX read/write, no other deps)
 * Errors: one line on stderr, exit status 2.
 */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define MAX_CH 16
#define MAX_LINE 65536
#define BUF 65536

/* ------------------------------------------------------------------ buffered I/O */
static unsigned char in_buf[BUF];
static size_t in_pos = 0, in_len = 0;
static unsigned char out_buf[BUF];
static size_t out_len = 0;
static long long sample_no = 0; /* the index of the sample being read (for messages) */

static void flush_out(void);

static void die(const char *msg) {
    flush_out(); /* the answers so far are good: the harness then names the sample it stopped at */
    fprintf(stderr, "nmv_fixed: %s (at sample %lld)\n", msg, sample_no);
    exit(2);
}

static void flush_out(void) {
    size_t off = 0;
    while (off < out_len) {
        ssize_t w = write(1, out_buf + off, out_len - off);
        if (w < 0) {
            if (errno == EINTR) continue;
            exit(1); /* the harness closed its end: nothing left to tell it */
        }
        off += (size_t)w;
    }
    out_len = 0;
}

static void put_byte(unsigned char b) {
    if (out_len == BUF) flush_out();
    out_buf[out_len++] = b;
}

/* refill the input buffer; 0 at end of input. Answers are flushed first: we may block here. */
static int refill(void) {
    flush_out();
    for (;;) {
        ssize_t r = read(0, in_buf, BUF);
        if (r < 0 && errno == EINTR) continue;
        if (r < 0) die("cannot read stdin");
        in_pos = 0;
        in_len = (size_t)r;
        return r > 0;
    }
}

/* one line without its newline into line (NUL-terminated); 0 at end of input */
static int read_line(char *line, size_t cap) {
    size_t n = 0;
    for (;;) {
        if (in_pos == in_len && !refill()) {
            if (n == 0) return 0;
            break; /* a last line without a newline */
        }
        unsigned char ch = in_buf[in_pos++];
        if (ch == '\n') break;
        if (n + 1 >= cap) die("input line too long");
        line[n++] = (char)ch;
    }
    if (n && line[n - 1] == '\r') n--;
    line[n] = '\0';
    return 1;
}

/* exactly n bytes; 0 at a clean end of input, an error for a partial record */
static int read_bytes(unsigned char *dst, size_t n) {
    size_t got = 0;
    while (got < n) {
        if (in_pos == in_len && !refill()) {
            if (got == 0) return 0;
            die("input ends inside a float64 record");
        }
        size_t take = in_len - in_pos < n - got ? in_len - in_pos : n - got;
        memcpy(dst + got, in_buf + in_pos, take);
        in_pos += take;
        got += take;
    }
    return 1;
}

static double le_f64(const unsigned char *p) {
    uint64_t u = 0;
    for (int i = 7; i >= 0; i--) u = (u << 8) | p[i];
    double d;
    memcpy(&d, &u, sizeof d);
    return d;
}

/* ------------------------------------------------------------------ minimal JSON look-ups */
/* the value after "key": in s[from, to); NULL when absent */
static const char *json_value(const char *s, const char *from, const char *to, const char *key) {
    size_t k = strlen(key);
    for (const char *p = from; p && p + k + 2 <= to; p++) {
        p = strchr(p, '"');
        if (!p || p + k + 2 > to) return NULL;
        if (strncmp(p + 1, key, k) == 0 && p[k + 1] == '"') {
            const char *q = p + k + 2;
            while (*q == ' ' || *q == '\t') q++;
            if (*q == ':') {
                q++;
                while (*q == ' ' || *q == '\t') q++;
                return q;
            }
        }
    }
    (void)s;
    return NULL;
}

static double json_number(const char *v, const char *what) {
    char *end;
    double d = strtod(v, &end);
    if (end == v) {
        char msg[128];
        snprintf(msg, sizeof msg, "header: %s is not a number", what);
        die(msg);
    }
    return d;
}

/* the matching closing bracket of the object or array opening at p */
static const char *json_close(const char *p) {
    int depth = 0, in_str = 0;
    for (; *p; p++) {
        if (in_str) {
            if (*p == '\\' && p[1]) p++;
            else if (*p == '"') in_str = 0;
        } else if (*p == '"') in_str = 1;
        else if (*p == '{' || *p == '[') depth++;
        else if (*p == '}' || *p == ']') {
            if (--depth == 0) return p;
        }
    }
    die("header: unbalanced JSON");
    return NULL;
}

/* ------------------------------------------------------------------ the detector */
typedef struct {
    long n;               /* window N in samples */
    int frac_bits;        /* f */
    int64_t reg[3];       /* threshold registers T = rint(k sigma^2 2^f) */
    long need;            /* checks in a row for final static (eq. 8) */
    double lsb_g;         /* the count's step */
    int8_t *ring;         /* the last N counts per axis: ring[axis * N + pos] */
    long pos, since, run; /* ring position, samples since the reset, temporary statics in a row */
    int64_t s1[3], s2[3]; /* eq. 2-3: the window's sum and sum of squares */
    int decision;         /* the latest check's final static */
} nmv;

static void nmv_reset(nmv *d) {
    memset(d->ring, 0, (size_t)(3 * d->n));
    d->pos = d->since = d->run = 0;
    for (int a = 0; a < 3; a++) d->s1[a] = d->s2[a] = 0;
    d->decision = 0;
}

static int to_count(double g, double lsb) {
    double q = rint(g / lsb); /* round to nearest, ties to even, as the sensor model */
    if (q < -128.0) return -128;
    if (q > 127.0) return 127;
    return (int)q;
}

static int nmv_step(nmv *d, const double acc[3]) {
    const long n = d->n;
    for (int a = 0; a < 3; a++) {
        int64_t c = to_count(acc[a], d->lsb_g);
        int8_t *slot = &d->ring[a * n + d->pos];
        if (d->since >= n) { /* the window is full: the oldest sample leaves (eq. 2-3) */
            int64_t old = *slot;
            d->s1[a] -= old;
            d->s2[a] -= old * old;
        }
        *slot = (int8_t)c;
        d->s1[a] += c;
        d->s2[a] += c * c;
    }
    d->pos = d->pos + 1 == n ? 0 : d->pos + 1;
    d->since++;
    if (d->since >= n && d->since % n == 0) { /* a check every N samples */
        int temp = 1;
        const int64_t scale = (int64_t)1 << d->frac_bits;
        for (int a = 0; a < 3; a++) {
            int64_t dd = (int64_t)n * d->s2[a] - d->s1[a] * d->s1[a]; /* N^2 MV >= 0 */
            if (!(dd * scale < d->reg[a] * (int64_t)n * (int64_t)n)) temp = 0; /* eq. 7 */
        }
        d->run = temp ? d->run + 1 : 0;
        d->decision = temp && d->run >= d->need; /* eq. 8 */
    }
    return d->decision;
}

/* ------------------------------------------------------------------ main */
int main(void) {
    static char line[MAX_LINE];
    if (!read_line(line, sizeof line)) die("no header line on stdin");
    const char *end = line + strlen(line);

    const char *v = json_value(line, line, end, "fs_hz");
    if (!v) die("header: no fs_hz");
    double fs = json_number(v, "fs_hz");
    if (!(fs > 0)) die("header: fs_hz must be > 0");

    int f64 = 0;
    v = json_value(line, line, end, "framing");
    if (v) {
        if (strncmp(v, "\"f64\"", 5) == 0) f64 = 1;
        else if (strncmp(v, "\"csv\"", 5) != 0) die("header: framing must be \"csv\" or \"f64\"");
    }

    /* the channels: the columns of the accelerometer's three axes */
    v = json_value(line, line, end, "channels");
    if (!v || *v != '[') die("header: no channels array");
    const char *close = json_close(v);
    int nch = 0, col[3] = {-1, -1, -1};
    static const char *acc[3] = {"acc_x_g", "acc_y_g", "acc_z_g"};
    for (const char *p = v; p < close; p++) {
        if (*p != '"') continue;
        const char *q = strchr(p + 1, '"');
        if (!q || q > close) die("header: bad channels array");
        if (nch == MAX_CH) die("header: too many channels");
        for (int a = 0; a < 3; a++)
            if ((size_t)(q - p - 1) == strlen(acc[a]) && strncmp(p + 1, acc[a], strlen(acc[a])) == 0) col[a] = nch;
        nch++;
        p = q;
    }
    for (int a = 0; a < 3; a++)
        if (col[a] < 0) die("header: channels must include acc_x_g, acc_y_g and acc_z_g");

    /* the parameters */
    double window_s = 1.0, k = 4.0, tth = 4.0, lsb = 0.018, s2[3] = {1.0 / 12, 1.0 / 12, 1.0 / 12};
    int frac_bits = 8;
    const char *pf = json_value(line, line, end, "params"), *pe = end;
    if (pf && *pf == '{') {
        pe = json_close(pf);
        if ((v = json_value(line, pf, pe, "window_s"))) window_s = json_number(v, "window_s");
        if ((v = json_value(line, pf, pe, "k"))) k = json_number(v, "k");
        if ((v = json_value(line, pf, pe, "time_threshold_s"))) tth = json_number(v, "time_threshold_s");
        if ((v = json_value(line, pf, pe, "lsb_g"))) lsb = json_number(v, "lsb_g");
        if ((v = json_value(line, pf, pe, "frac_bits"))) frac_bits = (int)json_number(v, "frac_bits");
        const char *sc = json_value(line, pf, pe, "sigma2_counts");
        double scale = 1.0; /* "sigma2" in g^2 when there is no "sigma2_counts": over lsb_g^2 */
        if (!sc && (sc = json_value(line, pf, pe, "sigma2"))) scale = lsb * lsb;
        if ((v = sc)) {
            if (*v == '[') {
                const char *p = v + 1;
                for (int a = 0; a < 3; a++) {
                    char *e;
                    s2[a] = strtod(p, &e);
                    if (e == p) die("header: sigma2_counts must be one number or three");
                    p = e;
                    while (*p == ' ' || *p == ',') p++;
                }
            } else {
                s2[0] = s2[1] = s2[2] = json_number(v, "sigma2_counts");
            }
            for (int a = 0; a < 3; a++) s2[a] /= scale;
        }
    }
    if (!(window_s > 0) || !(k > 0) || !(tth > 0) || !(lsb > 0)) die("params: window_s, k, time_threshold_s, lsb_g must be > 0");
    if (frac_bits < 0 || frac_bits > 16) die("params: frac_bits must be in 0-16");
    for (int a = 0; a < 3; a++)
        if (!(s2[a] > 0)) die("params: sigma2_counts must be > 0");

    nmv d;
    d.n = lrint(window_s * fs); /* round half to even, as Python's round */
    if (d.n < 2 || d.n > 65536) die("params: the window must be 2-65536 samples");
    d.frac_bits = frac_bits;
    d.lsb_g = lsb;
    d.need = (long)ceil(tth / window_s - 1e-9);
    if (d.need < 1) d.need = 1;
    for (int a = 0; a < 3; a++) d.reg[a] = llrint(k * s2[a] * (double)((int64_t)1 << frac_bits));
    d.ring = malloc((size_t)(3 * d.n));
    if (!d.ring) die("out of memory");
    nmv_reset(&d);

    const double period = 1.0 / fs;
    double t_prev = 0.0, x[MAX_CH + 1];
    int have_prev = 0;
    unsigned char rec[8 * (MAX_CH + 1)];
    for (;; sample_no++) {
        if (f64) {
            if (!read_bytes(rec, (size_t)(8 * (nch + 1)))) break;
            for (int j = 0; j <= nch; j++) x[j] = le_f64(rec + 8 * j);
        } else {
            if (!read_line(line, sizeof line)) break;
            char *p = line, *e;
            for (int j = 0; j <= nch; j++) {
                x[j] = strtod(p, &e);
                if (e == p || (j < nch && *e != ',') || (j == nch && *e != '\0')) die("a CSV line needs t_s and one number per channel");
                p = e + 1;
            }
        }
        for (int j = 0; j <= nch; j++)
            if (!isfinite(x[j])) die("NaN or inf in the sample");
        if (have_prev && !(x[0] > t_prev)) die("time is not increasing");
        if (have_prev && x[0] - t_prev > 1.5 * period) nmv_reset(&d); /* a gap resets the detector */
        t_prev = x[0];
        have_prev = 1;
        double a3[3] = {x[1 + col[0]], x[1 + col[1]], x[1 + col[2]]};
        int out = nmv_step(&d, a3);
        if (f64) put_byte((unsigned char)out);
        else {
            put_byte(out ? '1' : '0');
            put_byte('\n');
        }
    }
    flush_out();
    free(d.ring);
    return 0;
}
