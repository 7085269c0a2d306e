// SPDX-License-Identifier: GPL-2.0
/*
 * The calibration record and its text format (daemon/RECORD.md).
 *
 * Writing is canonical: one key per line in a fixed order, then a crc32
 * line over every byte before it. Reading is strict: every key exactly
 * once, nothing unknown, every value in range, the checksum right; a
 * record that fails any of this is never used.
 */
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

#include "common/record.h"

#define Q16_ONE			65536
#define MICRO			1000000
#define MILLI			1000
/* Level means are kept to 1e-6 LSB in the file: Q16 round-trips exactly */
#define LEVEL_MEAN_MAX_MICRO	(2048LL * MICRO)
#define T_LEVEL_MIN_MDEGC	(-30000)
#define T_LEVEL_MAX_MDEGC	85000
#define LINE_MAX_LEN		256

enum record_key {
	KEY_FORMAT,
	KEY_CHIP,
	KEY_CREATED,
	KEY_EEPROM,
	KEY_DAC,
	KEY_LEVEL_MEAN,
	KEY_T_LEVEL,
	KEY_GRAVITY,
	KEY_SAMPLES,
	KEY_LPF,
	KEY_SOURCE,
	KEY_MAGN_HARD_IRON,
	KEY_MAGN_SOFT_IRON,
	KEY_MAGN_FIELD,
	KEY_MAGN_RESIDUAL,
	KEY_MAGN_COVERAGE,
	KEY_MAGN_SAMPLES,
	KEY_MAGN_LEARNED,
	KEY_MAGN_ROTATION,	/* <record>.magn only */
	KEY_CRC32,
	KEY_COUNT,
};

static const char *const key_names[KEY_COUNT] = {
	[KEY_FORMAT] = "format",
	[KEY_CHIP] = "chip",
	[KEY_CREATED] = "created",
	[KEY_EEPROM] = "eeprom",
	[KEY_DAC] = "dac",
	[KEY_LEVEL_MEAN] = "level_mean",
	[KEY_T_LEVEL] = "t_level",
	[KEY_GRAVITY] = "gravity",
	[KEY_SAMPLES] = "samples",
	[KEY_LPF] = "lpf",
	[KEY_SOURCE] = "source",
	[KEY_MAGN_HARD_IRON] = "magn_hard_iron",
	[KEY_MAGN_SOFT_IRON] = "magn_soft_iron",
	[KEY_MAGN_FIELD] = "magn_field",
	[KEY_MAGN_RESIDUAL] = "magn_residual",
	[KEY_MAGN_COVERAGE] = "magn_coverage",
	[KEY_MAGN_SAMPLES] = "magn_samples",
	[KEY_MAGN_LEARNED] = "magn_learned",
	[KEY_MAGN_ROTATION] = "magn_rotation",
	[KEY_CRC32] = "crc32",
};

/* The keys of the magnetometer section: all of them in format 2, none in 1 */
static bool is_magn_key(int key)
{
	return key >= KEY_MAGN_HARD_IRON && key <= KEY_MAGN_LEARNED;
}

uint64_t record_fingerprint(const uint8_t eeprom[AS9888_EEPROM_LEN])
{
	uint64_t h = 0xcbf29ce484222325ULL;
	int i;

	for (i = 0; i < AS9888_EEPROM_LEN; i++) {
		h ^= eeprom[i];
		h *= 0x100000001b3ULL;
	}

	return h;
}

/* CRC-32 (IEEE 802.3, reflected, as zlib's crc32()) */
uint32_t record_crc32(const void *data, size_t len)
{
	const uint8_t *p = data;
	uint32_t crc = 0xffffffffu;
	int bit;

	while (len--) {
		crc ^= *p++;
		for (bit = 0; bit < 8; bit++)
			crc = (crc >> 1) ^ (0xedb88320u & -(crc & 1));
	}

	return ~crc;
}

static int fail(char *err, size_t errlen, const char *fmt, ...)
	__attribute__((format(printf, 3, 4)));

static int fail(char *err, size_t errlen, const char *fmt, ...)
{
	va_list ap;

	if (err && errlen) {
		va_start(ap, fmt);
		vsnprintf(err, errlen, fmt, ap);
		va_end(ap);
	}

	return -EINVAL;
}

/* Rrot: orthonormal (R R^T = I, det 1) and a turn of at most 5 degrees */
static int rotation_validate(const int32_t r[AS9888_AXES][AS9888_AXES],
			     char *err, size_t errlen)
{
	double det, trace = 0;
	int i, j, k;

	for (i = 0; i < AS9888_AXES; i++) {
		trace += r[i][i] / (double)MICRO;
		for (j = 0; j < AS9888_AXES; j++) {
			double dot = 0;

			for (k = 0; k < AS9888_AXES; k++)
				dot += (double)r[i][k] * r[j][k] /
				       ((double)MICRO * MICRO);
			if (fabs(dot - (i == j)) > RECORD_MAGN_ROT_TOLERANCE)
				return fail(err, errlen, "magn_rotation is not a rotation (rows %d and %d)",
					    i, j);
		}
	}
	det = ((double)r[0][0] * ((double)r[1][1] * r[2][2] - (double)r[1][2] * r[2][1]) -
	       (double)r[0][1] * ((double)r[1][0] * r[2][2] - (double)r[1][2] * r[2][0]) +
	       (double)r[0][2] * ((double)r[1][0] * r[2][1] - (double)r[1][1] * r[2][0])) /
	      ((double)MICRO * MICRO * MICRO);
	if (det < 0)
		return fail(err, errlen, "magn_rotation is a reflection, not a rotation");
	if (trace < 1 + 2 * cos(RECORD_MAGN_ROT_MAX_DEG * M_PI / 180) -
		     RECORD_MAGN_ROT_TOLERANCE)
		return fail(err, errlen, "magn_rotation turns by more than %d degrees",
			    RECORD_MAGN_ROT_MAX_DEG);

	return 0;
}

int record_magn_validate(const struct calib_magn *m, char *err, size_t errlen)
{
	int i, j;

	for (i = 0; i < AS9888_AXES; i++) {
		if (m->hard_iron_nt[i] > RECORD_MAGN_BIAS_MAX_NT ||
		    m->hard_iron_nt[i] < -RECORD_MAGN_BIAS_MAX_NT)
			return fail(err, errlen, "magnetometer hard iron of axis %c is beyond +-1000 uT",
				    "XYZ"[i]);
		for (j = 0; j < AS9888_AXES; j++) {
			int32_t w = m->soft_iron_micro[i][j];

			if (i == j && (w < RECORD_MAGN_DIAG_MIN_MICRO ||
				       w > RECORD_MAGN_DIAG_MAX_MICRO))
				return fail(err, errlen, "soft-iron gain %d,%d is outside 0.5..2",
					    i, j);
			if (i != j && (w > RECORD_MAGN_CROSS_MAX_MICRO ||
				       w < -RECORD_MAGN_CROSS_MAX_MICRO))
				return fail(err, errlen, "soft-iron term %d,%d is beyond +-0.5",
					    i, j);
			if (w != m->soft_iron_micro[j][i])
				return fail(err, errlen, "soft-iron matrix is not symmetric (%d,%d)",
					    i, j);
		}
	}
	if (m->field_nt < RECORD_MAGN_FIELD_MIN_NT ||
	    m->field_nt > RECORD_MAGN_FIELD_MAX_NT)
		return fail(err, errlen, "fitted field %.3f uT is outside the Earth's 20..70 uT",
			    m->field_nt / 1000.0);
	if (m->residual_nt < 0 || m->residual_nt > RECORD_MAGN_RESIDUAL_MAX_NT)
		return fail(err, errlen, "fit residual %.3f uT is outside 0..20 uT",
			    m->residual_nt / 1000.0);
	if (m->coverage_milli < 0 || m->coverage_milli > MILLI)
		return fail(err, errlen, "coverage %.3f is outside 0..1",
			    m->coverage_milli / 1000.0);
	if (m->samples < RECORD_MAGN_SAMPLES_MIN ||
	    m->samples > RECORD_MAGN_SAMPLES_MAX)
		return fail(err, errlen, "magnetometer sample count %u is outside %d..%d",
			    m->samples, RECORD_MAGN_SAMPLES_MIN,
			    RECORD_MAGN_SAMPLES_MAX);
	if (m->learned < 0)
		return fail(err, errlen, "magnetometer calibration time is before 1970");

	return m->has_rotation ? rotation_validate(m->rotation_micro, err, errlen) :
				 0;
}

int record_validate(const struct calib_record *rec, char *err, size_t errlen)
{
	struct as9888_eeprom ee;
	int axis, vertical = 0;

	if (as9888_eeprom_decode(rec->eeprom, &ee))
		return fail(err, errlen, "EEPROM data is not usable (errors 0x%x)",
			    ee.errors);
	for (axis = 0; axis < AS9888_AXES; axis++) {
		int64_t micro = (int64_t)rec->level_mean_q16[axis] * MICRO / Q16_ONE;

		if (!as9888_dac_valid(rec->dac[axis]))
			return fail(err, errlen, "DAC value 0x%02x of axis %c is outside 0..67 and 128..195",
				    rec->dac[axis], "XYZ"[axis]);
		if (micro > LEVEL_MEAN_MAX_MICRO || micro < -LEVEL_MEAN_MAX_MICRO)
			return fail(err, errlen, "level mean of axis %c is beyond +-2048 LSB",
				    "XYZ"[axis]);
		if (rec->gravity[axis] < -1 || rec->gravity[axis] > 1)
			return fail(err, errlen, "gravity component %d is not -1, 0 or 1",
				    rec->gravity[axis]);
		vertical += rec->gravity[axis] != 0;
	}
	if (vertical != 1)
		return fail(err, errlen, "gravity must point along exactly one axis");
	if (rec->t_level_mdegc < T_LEVEL_MIN_MDEGC ||
	    rec->t_level_mdegc > T_LEVEL_MAX_MDEGC)
		return fail(err, errlen, "level-test temperature %.3f degC is outside -30..85 degC",
			    rec->t_level_mdegc / 1000.0);
	if (rec->samples < AS9888_SAMPLES_MIN || rec->samples > AS9888_SAMPLES_MAX)
		return fail(err, errlen, "sample count %u is outside %d..%d",
			    rec->samples, AS9888_SAMPLES_MIN, AS9888_SAMPLES_MAX);
	if (rec->created < 0)
		return fail(err, errlen, "creation time is before 1970");

	return rec->magn.present ? record_magn_validate(&rec->magn, err, errlen) : 0;
}

/* Print a fixed-point value with @decimals exact decimals */
static int print_fixed(char *buf, size_t size, int64_t value, int64_t scale,
		       int decimals)
{
	uint64_t mag = value < 0 ? -(uint64_t)value : (uint64_t)value;

	return snprintf(buf, size, "%s%llu.%0*llu", value < 0 ? "-" : "",
			(unsigned long long)(mag / scale), decimals,
			(unsigned long long)(mag % scale));
}

static int64_t q16_to_micro(int32_t q16)
{
	int64_t num = (int64_t)q16 * MICRO;

	/* round half away from zero; exact inverse of micro_to_q16() */
	return (num + (num < 0 ? -Q16_ONE / 2 : Q16_ONE / 2)) / Q16_ONE;
}

static int32_t micro_to_q16(int64_t micro)
{
	int64_t num = micro * Q16_ONE;

	return (int32_t)((num + (num < 0 ? -MICRO / 2 : MICRO / 2)) / MICRO);
}

static int format_time(int64_t t, char *buf, size_t size)
{
	time_t when = (time_t)t;
	struct tm tm;

	if (!gmtime_r(&when, &tm) ||
	    !strftime(buf, size, "%Y-%m-%dT%H:%M:%SZ", &tm))
		return -EINVAL;

	return 0;
}

/* snprintf() appended at @len; the new length or -ENOSPC */
static int append(char *buf, size_t size, size_t len, const char *fmt, ...)
	__attribute__((format(printf, 4, 5)));

static int append(char *buf, size_t size, size_t len, const char *fmt, ...)
{
	va_list ap;
	int n;

	if (len >= size)
		return -ENOSPC;
	va_start(ap, fmt);
	n = vsnprintf(buf + len, size - len, fmt, ap);
	va_end(ap);
	if (n < 0 || (size_t)n >= size - len)
		return -ENOSPC;

	return (int)(len + (size_t)n);
}

/* The magnetometer section of format 2, appended at @len */
static int format_magn(const struct calib_magn *m, bool rotation, char *buf,
		       size_t size, size_t len)
{
	char v[AS9888_AXES * AS9888_AXES][32], learned[32];
	int i, n;

	if (format_time(m->learned, learned, sizeof(learned)))
		return -EINVAL;
	for (i = 0; i < AS9888_AXES; i++)
		print_fixed(v[i], sizeof(v[i]), m->hard_iron_nt[i], MILLI, 3);
	n = append(buf, size, len, "magn_hard_iron = %s %s %s\n", v[0], v[1], v[2]);
	if (n < 0)
		return n;
	for (i = 0; i < AS9888_AXES * AS9888_AXES; i++)
		print_fixed(v[i], sizeof(v[i]),
			    m->soft_iron_micro[i / AS9888_AXES][i % AS9888_AXES],
			    MICRO, 6);
	n = append(buf, size, (size_t)n,
		   "magn_soft_iron = %s %s %s %s %s %s %s %s %s\n",
		   v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7], v[8]);
	for (i = 0; rotation && n >= 0 && i < AS9888_AXES * AS9888_AXES; i++)
		print_fixed(v[i], sizeof(v[i]),
			    m->has_rotation ?
			    m->rotation_micro[i / AS9888_AXES][i % AS9888_AXES] :
			    (i % (AS9888_AXES + 1) ? 0 : MICRO), MICRO, 6);
	if (rotation && n >= 0)
		n = append(buf, size, (size_t)n,
			   "magn_rotation = %s %s %s %s %s %s %s %s %s\n",
			   v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7], v[8]);
	if (n < 0)
		return n;
	print_fixed(v[0], sizeof(v[0]), m->field_nt, MILLI, 3);
	print_fixed(v[1], sizeof(v[1]), m->residual_nt, MILLI, 3);
	print_fixed(v[2], sizeof(v[2]), m->coverage_milli, MILLI, 3);

	return append(buf, size, (size_t)n,
		      "magn_field = %s\n"
		      "magn_residual = %s\n"
		      "magn_coverage = %s\n"
		      "magn_samples = %u\n"
		      "magn_learned = %s\n",
		      v[0], v[1], v[2], m->samples, learned);
}

/* The crc32 line over @buf's @len bytes appended: the total length or -ENOSPC */
static int seal(char *buf, size_t size, size_t len)
{
	return append(buf, size, len, "crc32 = %08x\n", record_crc32(buf, len));
}

int record_format(const struct calib_record *rec, char *buf, size_t size)
{
	char mean[AS9888_AXES][32], t_level[32], created[32];
	const uint8_t *e = rec->eeprom;
	size_t len;
	int axis, n;

	for (axis = 0; axis < AS9888_AXES; axis++)
		print_fixed(mean[axis], sizeof(mean[axis]),
			    q16_to_micro(rec->level_mean_q16[axis]), MICRO, 6);
	print_fixed(t_level, sizeof(t_level), rec->t_level_mdegc, MILLI, 3);
	if (format_time(rec->created, created, sizeof(created)))
		return -EINVAL;

	n = snprintf(buf, size,
		     "# AS9888 %s calibration, written by as9888-calibd.\n"
		     "# Do not edit: the crc32 line covers every byte above it.\n"
		     "format = %s %d\n"
		     "chip = %016llx\n"
		     "created = %s\n"
		     "eeprom = %02x %02x %02x %02x %02x %02x %02x %02x %02x %02x %02x"
		     " %02x %02x %02x %02x %02x %02x %02x %02x %02x %02x\n"
		     "dac = %02x %02x %02x\n"
		     "level_mean = %s %s %s\n"
		     "t_level = %s\n"
		     "gravity = %d %d %d\n"
		     "samples = %u\n"
		     "lpf = %s\n",
		     rec->magn.present ? "accelerometer and magnetometer" :
		     "accelerometer",
		     RECORD_FORMAT_NAME, rec->magn.present ? RECORD_FORMAT_MAGN :
		     RECORD_FORMAT_VERSION,
		     (unsigned long long)record_fingerprint(e), created,
		     e[0], e[1], e[2], e[3], e[4], e[5], e[6], e[7], e[8], e[9],
		     e[10], e[11], e[12], e[13], e[14], e[15], e[16], e[17],
		     e[18], e[19], e[20],
		     rec->dac[0], rec->dac[1], rec->dac[2],
		     mean[0], mean[1], mean[2], t_level,
		     rec->gravity[0], rec->gravity[1], rec->gravity[2],
		     rec->samples, rec->lpf ? "on" : "off");
	if (n < 0 || (size_t)n >= size)
		return -ENOSPC;
	len = (size_t)n;
	if (rec->simulated) {
		n = append(buf, size, len, "source = simulator\n");
		if (n < 0)
			return n;
		len = (size_t)n;
	}
	if (rec->magn.present) {
		n = format_magn(&rec->magn, false, buf, size, len);
		if (n < 0)
			return n;
		len = (size_t)n;
	}

	return seal(buf, size, len);
}

int record_magn_format(const struct calib_magn *m,
		       const uint8_t eeprom[AS9888_EEPROM_LEN], int64_t created,
		       char *buf, size_t size)
{
	char when[32];
	int n;

	if (format_time(created, when, sizeof(when)))
		return -EINVAL;
	n = append(buf, size, 0,
		   "# AS9888 magnetometer calibration, written by as9888-calibd.\n"
		   "# Do not edit: the crc32 line covers every byte above it.\n"
		   "%s"
		   "format = %s %d\n"
		   "chip = %016llx\n"
		   "created = %s\n",
		   m->present ? "" : "# None (what rollback restores after the first one).\n",
		   RECORD_MAGN_FILE_NAME, RECORD_MAGN_FILE_VERSION,
		   (unsigned long long)record_fingerprint(eeprom), when);
	if (n >= 0 && m->present)
		n = format_magn(m, true, buf, size, (size_t)n);

	return n < 0 ? n : seal(buf, size, (size_t)n);
}

/* A cursor over one value: whitespace-separated tokens */
struct cursor {
	const char *p;
	const char *end;
};

static bool next_token(struct cursor *c, const char **tok, size_t *len)
{
	while (c->p < c->end && (*c->p == ' ' || *c->p == '\t'))
		c->p++;
	if (c->p == c->end)
		return false;
	*tok = c->p;
	while (c->p < c->end && *c->p != ' ' && *c->p != '\t')
		c->p++;
	*len = (size_t)(c->p - *tok);

	return true;
}

static bool at_end(struct cursor *c)
{
	const char *tok;
	size_t len;

	return !next_token(c, &tok, &len);
}

static int hex_digit(char ch)
{
	if (ch >= '0' && ch <= '9')
		return ch - '0';
	if (ch >= 'a' && ch <= 'f')
		return ch - 'a' + 10;
	return -1;
}

/* exactly @digits lower-case hex digits */
static bool parse_hex_u64(struct cursor *c, size_t digits, uint64_t *out)
{
	const char *tok;
	size_t len, i;

	if (!next_token(c, &tok, &len) || len != digits)
		return false;
	*out = 0;
	for (i = 0; i < len; i++) {
		int d = hex_digit(tok[i]);

		if (d < 0)
			return false;
		*out = *out << 4 | (uint64_t)d;
	}

	return true;
}

/* exactly two lower-case hex digits */
static bool parse_hex_byte(struct cursor *c, uint8_t *out)
{
	uint64_t v;

	if (!parse_hex_u64(c, 2, &v))
		return false;
	*out = (uint8_t)v;

	return true;
}

/*
 * A decimal with exactly @decimals digits after the point (0: an integer
 * without a point), in [@lo, @hi] after scaling by 10^@decimals.
 */
static bool parse_fixed(struct cursor *c, int decimals, int64_t lo, int64_t hi,
			int64_t *out)
{
	const char *tok, *p, *end;
	bool neg = false;
	int64_t v = 0;
	size_t len;
	int digits = 0, frac = -1;

	if (!next_token(c, &tok, &len))
		return false;
	p = tok;
	end = tok + len;
	if (p < end && *p == '-') {
		neg = true;
		p++;
	}
	if (p == end)
		return false;
	for (; p < end; p++) {
		if (*p == '.' && frac < 0 && digits > 0) {
			frac = 0;
			continue;
		}
		if (*p < '0' || *p > '9')
			return false;
		if (++digits > 15)
			return false;
		v = v * 10 + (*p - '0');
		if (frac >= 0)
			frac++;
	}
	if (decimals ? frac != decimals : frac >= 0)
		return false;
	if (neg)
		v = -v;
	if (v < lo || v > hi)
		return false;
	*out = v;

	return true;
}

static bool parse_time(struct cursor *c, int64_t *out)
{
	const char *tok;
	char text[32];
	struct tm tm;
	size_t len;
	char *end;
	time_t t;

	if (!next_token(c, &tok, &len) || len != 20)
		return false;
	memcpy(text, tok, len);
	text[len] = '\0';
	memset(&tm, 0, sizeof(tm));
	end = strptime(text, "%Y-%m-%dT%H:%M:%SZ", &tm);
	if (!end || *end)
		return false;
	t = timegm(&tm);
	if (t == (time_t)-1)
		return false;
	*out = t;

	return true;
}

/* One of two words: @yes sets *@v, @no clears it */
static bool parse_choice(struct cursor *c, const char *yes, const char *no,
			 bool *v)
{
	const char *tok;
	size_t len;

	if (!next_token(c, &tok, &len))
		return false;
	if (len == strlen(yes) && !memcmp(tok, yes, len))
		*v = true;
	else if (len == strlen(no) && !memcmp(tok, no, len))
		*v = false;
	else
		return false;

	return true;
}

/* @n fixed-point values with @decimals decimals within +-@max into @out */
static bool parse_fixed_n(struct cursor *c, int n, int decimals, int64_t min,
			  int64_t max, int32_t *out)
{
	int64_t v;
	int i;

	for (i = 0; i < n; i++) {
		if (!parse_fixed(c, decimals, min, max, &v))
			return false;
		out[i] = (int32_t)v;
	}

	return true;
}

/* The magnetometer section's values (ranges: record_magn_validate()) */
static bool parse_magn_value(enum record_key key, struct cursor *c,
			     struct calib_magn *m)
{
	int64_t v;

	switch (key) {
	case KEY_MAGN_HARD_IRON:
		return parse_fixed_n(c, AS9888_AXES, 3, -RECORD_MAGN_BIAS_MAX_NT,
				     RECORD_MAGN_BIAS_MAX_NT, m->hard_iron_nt);
	case KEY_MAGN_SOFT_IRON:
		return parse_fixed_n(c, AS9888_AXES * AS9888_AXES, 6,
				     -RECORD_MAGN_DIAG_MAX_MICRO,
				     RECORD_MAGN_DIAG_MAX_MICRO,
				     &m->soft_iron_micro[0][0]);
	case KEY_MAGN_FIELD:
		return parse_fixed_n(c, 1, 3, RECORD_MAGN_FIELD_MIN_NT,
				     RECORD_MAGN_FIELD_MAX_NT, &m->field_nt);
	case KEY_MAGN_RESIDUAL:
		return parse_fixed_n(c, 1, 3, 0, RECORD_MAGN_RESIDUAL_MAX_NT,
				     &m->residual_nt);
	case KEY_MAGN_COVERAGE:
		return parse_fixed_n(c, 1, 3, 0, MILLI, &m->coverage_milli);
	case KEY_MAGN_SAMPLES:
		if (!parse_fixed(c, 0, RECORD_MAGN_SAMPLES_MIN,
				 RECORD_MAGN_SAMPLES_MAX, &v))
			return false;
		m->samples = (uint32_t)v;
		return true;
	case KEY_MAGN_LEARNED:
		return parse_time(c, &m->learned);
	default:
		return false;
	}
}

static bool parse_value(enum record_key key, struct cursor *c,
			struct calib_record *rec, bool magn_file,
			uint64_t *chip, int64_t *version)
{
	const char *name = magn_file ? RECORD_MAGN_FILE_NAME : RECORD_FORMAT_NAME;
	const char *tok;
	int64_t v;
	size_t len;
	int i;

	if (is_magn_key(key))
		return parse_magn_value(key, c, &rec->magn);
	switch (key) {
	case KEY_FORMAT:
		if (!next_token(c, &tok, &len) || len != strlen(name) ||
		    memcmp(tok, name, len))
			return false;
		return magn_file ?
		       parse_fixed(c, 0, RECORD_MAGN_FILE_VERSION,
				   RECORD_MAGN_FILE_VERSION, version) :
		       parse_fixed(c, 0, RECORD_FORMAT_VERSION,
				   RECORD_FORMAT_MAGN, version);
	case KEY_MAGN_ROTATION:
		return parse_fixed_n(c, AS9888_AXES * AS9888_AXES, 6, -MICRO,
				     MICRO, &rec->magn.rotation_micro[0][0]);
	case KEY_CHIP:
		return parse_hex_u64(c, 16, chip);
	case KEY_CREATED:
		return parse_time(c, &rec->created);
	case KEY_EEPROM:
		for (i = 0; i < AS9888_EEPROM_LEN; i++)
			if (!parse_hex_byte(c, &rec->eeprom[i]))
				return false;
		return true;
	case KEY_DAC:
		for (i = 0; i < AS9888_AXES; i++)
			if (!parse_hex_byte(c, &rec->dac[i]))
				return false;
		return true;
	case KEY_LEVEL_MEAN:
		for (i = 0; i < AS9888_AXES; i++) {
			if (!parse_fixed(c, 6, -LEVEL_MEAN_MAX_MICRO,
					 LEVEL_MEAN_MAX_MICRO, &v))
				return false;
			rec->level_mean_q16[i] = micro_to_q16(v);
		}
		return true;
	case KEY_T_LEVEL:
		if (!parse_fixed(c, 3, T_LEVEL_MIN_MDEGC, T_LEVEL_MAX_MDEGC, &v))
			return false;
		rec->t_level_mdegc = (int32_t)v;
		return true;
	case KEY_GRAVITY:
		for (i = 0; i < AS9888_AXES; i++) {
			if (!parse_fixed(c, 0, -1, 1, &v))
				return false;
			rec->gravity[i] = (int8_t)v;
		}
		return true;
	case KEY_SAMPLES:
		if (!parse_fixed(c, 0, AS9888_SAMPLES_MIN, AS9888_SAMPLES_MAX, &v))
			return false;
		rec->samples = (uint32_t)v;
		return true;
	case KEY_LPF:
		return parse_choice(c, "on", "off", &rec->lpf);
	case KEY_SOURCE:
		return parse_choice(c, "simulator", "chip", &rec->simulated);
	default:
		return false;
	}
}

static const char *const value_help[KEY_COUNT] = {
	[KEY_FORMAT] = "\"" RECORD_FORMAT_NAME " 1\" or \"" RECORD_FORMAT_NAME " 2\"",
	[KEY_CHIP] = "16 hex digits",
	[KEY_CREATED] = "YYYY-MM-DDTHH:MM:SSZ",
	[KEY_EEPROM] = "21 two-digit hex bytes",
	[KEY_DAC] = "3 two-digit hex bytes",
	[KEY_LEVEL_MEAN] = "3 numbers with 6 decimals within +-2048",
	[KEY_T_LEVEL] = "a number with 3 decimals within -30..85",
	[KEY_GRAVITY] = "3 integers -1, 0 or 1",
	[KEY_SAMPLES] = "an integer 10..4096",
	[KEY_LPF] = "on or off",
	[KEY_SOURCE] = "simulator or chip",
	[KEY_MAGN_HARD_IRON] = "3 numbers in uT with 3 decimals within +-1000",
	[KEY_MAGN_SOFT_IRON] = "9 numbers with 6 decimals within +-2",
	[KEY_MAGN_FIELD] = "a number in uT with 3 decimals within 20..70",
	[KEY_MAGN_RESIDUAL] = "a number in uT with 3 decimals within 0..20",
	[KEY_MAGN_COVERAGE] = "a number with 3 decimals within 0..1",
	[KEY_MAGN_SAMPLES] = "an integer 10..1000000",
	[KEY_MAGN_LEARNED] = "YYYY-MM-DDTHH:MM:SSZ",
	[KEY_MAGN_ROTATION] = "9 numbers with 6 decimals within +-1",
	[KEY_CRC32] = "8 hex digits",
};

/* The keys a file may hold: the record's, or <record>.magn's */
static bool key_allowed(enum record_key key, bool magn_file)
{
	if (!magn_file)
		return key != KEY_MAGN_ROTATION;
	return key == KEY_FORMAT || key == KEY_CHIP || key == KEY_CREATED ||
	       key == KEY_CRC32 || key == KEY_MAGN_ROTATION || is_magn_key(key);
}

/*
 * Every line of @text: each key once, allowed in this kind of file, its
 * value valid, nothing after the checksum, the checksum right. The keys
 * seen into @seen.
 */
static int parse_lines(const char *text, size_t len, bool magn_file,
		       struct calib_record *rec, uint64_t *chip,
		       int64_t *version, bool seen[KEY_COUNT], char *err,
		       size_t errlen)
{
	const char *line = text, *end = text + len;
	uint32_t crc;
	int lineno = 0, k;

	memset(rec, 0, sizeof(*rec));
	if (len > RECORD_MAX_SIZE)
		return fail(err, errlen, "%zu bytes: too large for a record", len);

	while (line < end) {
		const char *nl = memchr(line, '\n', (size_t)(end - line));
		const char *eq, *key_end;
		struct cursor c;
		size_t key_len;
		enum record_key key;

		lineno++;
		if (!nl)
			return fail(err, errlen, "line %d: not terminated by a newline",
				    lineno);
		if (nl - line > LINE_MAX_LEN)
			return fail(err, errlen, "line %d: too long", lineno);
		if (memchr(line, '\0', (size_t)(nl - line)))
			return fail(err, errlen, "line %d: contains a NUL byte", lineno);
		if (seen[KEY_CRC32])
			return fail(err, errlen, "line %d: text after the crc32 line",
				    lineno);
		if (line == nl || *line == '#') {
			line = nl + 1;
			continue;
		}

		eq = memchr(line, '=', (size_t)(nl - line));
		if (!eq)
			return fail(err, errlen, "line %d: expected \"key = value\"",
				    lineno);
		key_end = eq;
		while (key_end > line && key_end[-1] == ' ')
			key_end--;
		key_len = (size_t)(key_end - line);
		for (k = 0; k < KEY_COUNT; k++)
			if (strlen(key_names[k]) == key_len &&
			    !memcmp(key_names[k], line, key_len) &&
			    key_allowed((enum record_key)k, magn_file))
				break;
		if (k == KEY_COUNT)
			return fail(err, errlen, "line %d: unknown key \"%.*s\"",
				    lineno, (int)(key_len > 32 ? 32 : key_len), line);
		key = (enum record_key)k;
		if (seen[key])
			return fail(err, errlen, "line %d: %s given twice", lineno,
				    key_names[key]);
		seen[key] = true;

		c.p = eq + 1;
		c.end = nl;
		if (key == KEY_CRC32) {
			uint64_t value;

			if (!parse_hex_u64(&c, 8, &value) || !at_end(&c))
				return fail(err, errlen, "line %d: crc32 must be %s",
					    lineno, value_help[key]);
			crc = (uint32_t)value;
			if (crc != record_crc32(text, (size_t)(line - text)))
				return fail(err, errlen, "line %d: checksum mismatch: the %s is corrupt",
					    lineno, magn_file ? "file" : "record");
		} else if (!parse_value(key, &c, rec, magn_file, chip, version) ||
			   !at_end(&c)) {
			return fail(err, errlen, "line %d: %s must be %s", lineno,
				    key_names[key], magn_file && key == KEY_FORMAT ?
				    "\"" RECORD_MAGN_FILE_NAME " 1\"" :
				    value_help[key]);
		}
		line = nl + 1;
	}

	return 0;
}

int record_parse(const char *text, size_t len, struct calib_record *rec,
		 char *err, size_t errlen)
{
	bool seen[KEY_COUNT] = { false };
	uint64_t chip = 0;
	int64_t version = 0;
	bool magn_seen = false;
	int k, ret;

	ret = parse_lines(text, len, false, rec, &chip, &version, seen, err,
			  errlen);
	if (ret)
		return ret;

	for (k = 0; k < KEY_COUNT; k++) {
		if (is_magn_key(k)) {
			magn_seen |= seen[k];
			continue;
		}
		if (!seen[k] && k != KEY_SOURCE &&	/* optional: older records */
		    k != KEY_MAGN_ROTATION)		/* never in the record */
			return fail(err, errlen, "%s is missing%s", key_names[k],
				    k == KEY_CRC32 ? " (truncated record?)" : "");
	}
	/* format 2 has the whole magnetometer section, format 1 none of it */
	if (version == RECORD_FORMAT_VERSION && magn_seen)
		return fail(err, errlen, "magn_* keys need format %d, this record is format %d",
			    RECORD_FORMAT_MAGN, RECORD_FORMAT_VERSION);
	for (k = KEY_MAGN_HARD_IRON; version == RECORD_FORMAT_MAGN &&
	     k <= KEY_MAGN_LEARNED; k++)
		if (!seen[k])
			return fail(err, errlen, "%s is missing (format %d has the magnetometer's calibration)",
				    key_names[k], RECORD_FORMAT_MAGN);
	rec->magn.present = version == RECORD_FORMAT_MAGN;
	if (chip != record_fingerprint(rec->eeprom))
		return fail(err, errlen, "chip %016llx does not match the EEPROM data (%016llx)",
			    (unsigned long long)chip,
			    (unsigned long long)record_fingerprint(rec->eeprom));

	return record_validate(rec, err, errlen);
}

/* record_magn_parse(), with the file's "created" in @created */
static int magn_parse(const char *text, size_t len, struct calib_magn *m,
		      uint64_t *chip, int64_t *created, char *err, size_t errlen)
{
	bool seen[KEY_COUNT] = { false };
	struct calib_record rec;
	int64_t version = 0;
	int k, n = 0, ret;

	ret = parse_lines(text, len, true, &rec, chip, &version, seen, err,
			  errlen);
	if (ret)
		return ret;
	for (k = 0; k < KEY_COUNT; k++)
		if ((k == KEY_FORMAT || k == KEY_CHIP || k == KEY_CREATED ||
		     k == KEY_CRC32) && !seen[k])
			return fail(err, errlen, "%s is missing%s", key_names[k],
				    k == KEY_CRC32 ? " (truncated file?)" : "");
	for (k = KEY_MAGN_HARD_IRON; k <= KEY_MAGN_ROTATION; k++)
		n += seen[k];
	/* the whole calibration, or none (what rollback restores) */
	if (n && n != KEY_MAGN_ROTATION - KEY_MAGN_HARD_IRON + 1) {
		for (k = KEY_MAGN_HARD_IRON; seen[k]; k++)
			;
		return fail(err, errlen, "%s is missing (the file holds part of a calibration)",
			    key_names[k]);
	}
	*m = rec.magn;
	m->present = n > 0;
	m->has_rotation = m->present;
	*created = rec.created;

	return m->present ? record_magn_validate(m, err, errlen) : 0;
}

int record_magn_parse(const char *text, size_t len, struct calib_magn *m,
		      uint64_t *chip, char *err, size_t errlen)
{
	int64_t created;

	return magn_parse(text, len, m, chip, &created, err, errlen);
}

int record_magn_of(const struct calib_record *rec, const char *text,
		   size_t len, struct calib_magn *m, char *err, size_t errlen)
{
	char why[256], mine[32], its[32];
	uint64_t chip;
	int64_t created;

	if (magn_parse(text, len, m, &chip, &created, why, sizeof(why)))
		return fail(err, errlen, "not a valid magnetometer calibration: %s",
			    why);
	if (chip != record_fingerprint(rec->eeprom)) {
		fail(err, errlen, "of chip %016llx, the record's is %016llx",
		     (unsigned long long)chip,
		     (unsigned long long)record_fingerprint(rec->eeprom));
		return -EXDEV;
	}
	if (created == rec->created)
		return 0;
	if (format_time(created, its, sizeof(its)))
		snprintf(its, sizeof(its), "%lld", (long long)created);
	if (format_time(rec->created, mine, sizeof(mine)))
		snprintf(mine, sizeof(mine), "%lld", (long long)rec->created);
	fail(err, errlen, "of another change of the record (created %s, the record %s)",
	     its, mine);

	return -ESTALE;
}

int record_level_offsets(const struct calib_record *rec,
			 const struct as9888_eeprom *ee,
			 int32_t ot_l_q16[AS9888_AXES])
{
	int axis, ret;

	for (axis = 0; axis < AS9888_AXES; axis++) {
		int32_t st;

		ret = as9888_sensitivity_q16(&ee->axis[axis], ee->t_rt_mdegc,
					     rec->t_level_mdegc, &st);
		if (!ret)
			ret = as9888_offset_level_q16(rec->level_mean_q16[axis], st,
						      rec->gravity[axis],
						      &ot_l_q16[axis]);
		if (ret)
			return ret;
	}

	return 0;
}
