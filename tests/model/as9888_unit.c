// SPDX-License-Identifier: GPL-2.0
/*
 * AS9888 simulated unit: defaults and the parser of the datasheet section 8
 * text format. No libc, no floating point: builds in the kernel too.
 */

#include <linux/errno.h>
#include <linux/kernel.h>
#include <linux/math64.h>
#include <linux/types.h>

#include "as9888_unit.h"

static const u8 default_eeprom[AS9888_UNIT_EEPROM_LEN] = {
	0x9a, 0x71, 0x15, 0x5c, 0x80, 0x85, 0x7b, 0x1c, 0x63, 0xa2, 0x38,
	0xe6, 0x9c, 0x0d, 0x8f, 0x8c, 0x04, 0x65, 0xc3, 0x88, 0x50,
};

static const char *const fault_names[AS9888_FAULT_COUNT] = {
	"no_drdy", "int1_open", "int2_open", "rstn_open", "wia",
	"eeprom_blank", "stuck_x", "saturate_z", "nak", "selftest_weak",
	"hofl",
};

void as9888_unit_default(struct as9888_unit *u)
{
	int i;

	*u = (struct as9888_unit){ };
	for (i = 0; i < AS9888_UNIT_EEPROM_LEN; i++)
		u->eeprom[i] = default_eeprom[i];
	u->up[2] = AS9888_UNIT_UP_ONE;
	u->temperature_mdegc = 25000;
	u->noise_mlsb = 1000;
	u->field_nt[0] = 20000;
	u->field_nt[1] = -5000;
	u->field_nt[2] = -40000;
	u->orientation[0] = AS9888_UNIT_UP_ONE;
	for (i = 0; i < AS9888_UNIT_AXES; i++)
		u->soft_ppm[i * (AS9888_UNIT_AXES + 1)] = AS9888_UNIT_SOFT_ONE;
}

const char *as9888_fault_name(u32 fault_bit)
{
	int i;

	for (i = 0; i < AS9888_FAULT_COUNT; i++)
		if (fault_bit == BIT(i))
			return fault_names[i];
	return NULL;
}

u64 as9888_unit_isqrt(u64 x)
{
	u64 r = 0, bit = 1ULL << 62;

	while (bit > x)
		bit >>= 2;
	while (bit) {
		if (x >= r + bit) {
			x -= r + bit;
			r = (r >> 1) + bit;
		} else {
			r >>= 1;
		}
		bit >>= 2;
	}
	return r;
}

int as9888_unit_normalise(const s32 in[AS9888_UNIT_AXES],
			  s32 out[AS9888_UNIT_AXES])
{
	u64 sq = 0, norm;
	int i;

	for (i = 0; i < AS9888_UNIT_AXES; i++) {
		s64 c = in[i];

		sq += (u64)(c * c);
	}
	if (!sq)
		return -EINVAL;
	norm = as9888_unit_isqrt(sq);
	/* round the root to nearest: norm^2 <= sq < (norm + 1)^2 */
	if (sq - norm * norm > norm)
		norm++;
	for (i = 0; i < AS9888_UNIT_AXES; i++) {
		s64 c = in[i];
		s64 num = c * AS9888_UNIT_UP_ONE;
		s64 q = div64_s64(num < 0 ? -num : num, (s64)norm);
		s64 r = (num < 0 ? -num : num) - q * (s64)norm;

		if (2 * r >= (s64)norm)
			q++;
		if (q > AS9888_UNIT_UP_ONE)
			q = AS9888_UNIT_UP_ONE;
		out[i] = (s32)(num < 0 ? -q : q);
	}
	return 0;
}

/* ---- parser ---- */

struct cursor {
	const char *p;
	const char *end;
};

static bool is_space(char c)
{
	return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

static bool is_sep(char c)
{
	return is_space(c) || c == ',';
}

static bool is_digit(char c)
{
	return c >= '0' && c <= '9';
}

static int hex_val(char c)
{
	if (c >= '0' && c <= '9')
		return c - '0';
	if (c >= 'a' && c <= 'f')
		return c - 'a' + 10;
	if (c >= 'A' && c <= 'F')
		return c - 'A' + 10;
	return -1;
}

static void skip_seps(struct cursor *c)
{
	while (c->p < c->end && is_sep(*c->p))
		c->p++;
}

/* Next token (separated by spaces, tabs or commas); false if none. */
static bool next_token(struct cursor *c, struct cursor *tok)
{
	skip_seps(c);
	if (c->p >= c->end)
		return false;
	tok->p = c->p;
	while (c->p < c->end && !is_sep(*c->p))
		c->p++;
	tok->end = c->p;
	return true;
}

static bool tok_eq(const struct cursor *t, const char *s)
{
	const char *p = t->p;

	for (; *s; s++, p++)
		if (p >= t->end || *p != *s)
			return false;
	return p == t->end;
}

/* Error message builder (bounded, always NUL-terminated) */
struct msgbuf {
	char *buf;
	unsigned int pos;
};

static void msg_add(struct msgbuf *mb, const char *s)
{
	while (*s && mb->pos < AS9888_UNIT_ERROR_MSG_LEN - 1)
		mb->buf[mb->pos++] = *s++;
	mb->buf[mb->pos] = '\0';
}

/* Add a token, quoted, cut to 24 characters; non-printables as '?' */
static void msg_add_tok(struct msgbuf *mb, const struct cursor *t)
{
	const char *p;
	unsigned int n = 0;

	msg_add(mb, "'");
	for (p = t->p; p < t->end && n < 24; p++, n++) {
		char c[2] = { *p, '\0' };

		if (*p < 0x20 || *p > 0x7e)
			c[0] = '?';
		msg_add(mb, c);
	}
	if (p < t->end)
		msg_add(mb, "...");
	msg_add(mb, "'");
}

struct parse_state {
	struct as9888_unit_error *err;
	struct msgbuf mb;
	char scratch[AS9888_UNIT_ERROR_MSG_LEN];
	unsigned int line;
};

static int fail(struct parse_state *ps, const char *what,
		const struct cursor *tok, const char *tail)
{
	ps->mb.pos = 0;
	ps->mb.buf[0] = '\0';
	msg_add(&ps->mb, what);
	if (tok) {
		msg_add(&ps->mb, " ");
		msg_add_tok(&ps->mb, tok);
	}
	if (tail)
		msg_add(&ps->mb, tail);
	if (ps->err)
		ps->err->line = ps->line;
	return -EINVAL;
}

/*
 * Decimal "[+-]digits[.digits]" to an integer scaled by 10^@decimals,
 * |result| <= @max. Extra decimals are accepted only if zero.
 */
static int parse_decimal(struct parse_state *ps, const struct cursor *t,
			 int decimals, s64 max, const char *what, s64 *out)
{
	const char *p = t->p;
	bool neg = false, digits = false;
	s64 v = 0;
	int frac = -1;

	if (p < t->end && (*p == '+' || *p == '-')) {
		neg = *p == '-';
		p++;
	}
	for (; p < t->end; p++) {
		if (*p == '.' && frac < 0) {
			frac = 0;
			continue;
		}
		if (!is_digit(*p))
			return fail(ps, "malformed number", t, NULL);
		digits = true;
		if (frac >= decimals) {
			if (*p != '0')
				return fail(ps, "too many decimal places in",
					    t, NULL);
			continue;
		}
		if (frac >= 0)
			frac++;
		v = v * 10 + (*p - '0');
		if (v > max * 10)	/* way out of range: stop early */
			return fail(ps, what, t, " out of range");
	}
	if (!digits)
		return fail(ps, "malformed number", t, NULL);
	if (frac < 0)
		frac = 0;
	for (; frac < decimals; frac++) {
		v *= 10;
		if (v > max * 10)
			return fail(ps, what, t, " out of range");
	}
	if (v > max)
		return fail(ps, what, t, " out of range");
	*out = neg ? -v : v;
	return 0;
}

/* Exactly @n decimals separated by spaces/commas */
static int parse_vector(struct parse_state *ps, struct cursor *val, int n,
			int decimals, s64 max, const char *what, s64 *out)
{
	struct cursor tok;
	int i, ret;

	for (i = 0; i < n; i++) {
		if (!next_token(val, &tok))
			return fail(ps, what, NULL, ": too few values");
		ret = parse_decimal(ps, &tok, decimals, max, what, &out[i]);
		if (ret)
			return ret;
	}
	if (next_token(val, &tok))
		return fail(ps, what, NULL, ": too many values");
	return 0;
}

static int parse_eeprom(struct parse_state *ps, struct cursor *val,
			struct as9888_unit *u)
{
	u8 bytes[AS9888_UNIT_EEPROM_LEN];
	struct cursor tok;
	int i;

	for (i = 0; next_token(val, &tok); i++) {
		const char *p = tok.p;
		int v = 0;

		if (i >= AS9888_UNIT_EEPROM_LEN)
			return fail(ps, "eeprom: too many bytes (need 21)",
				    NULL, NULL);
		if (tok.end - p > 2 && p[0] == '0' && (p[1] == 'x' ||
						      p[1] == 'X'))
			p += 2;
		if (tok.end - p < 1 || tok.end - p > 2)
			return fail(ps, "eeprom: malformed byte", &tok, NULL);
		for (; p < tok.end; p++) {
			int h = hex_val(*p);

			if (h < 0)
				return fail(ps, "eeprom: malformed byte",
					    &tok, NULL);
			v = v * 16 + h;
		}
		bytes[i] = (u8)v;
	}
	if (i != AS9888_UNIT_EEPROM_LEN)
		return fail(ps, "eeprom: too few bytes (need 21)", NULL, NULL);
	for (i = 0; i < AS9888_UNIT_EEPROM_LEN; i++)
		u->eeprom[i] = bytes[i];
	return 0;
}

static int parse_seed(struct parse_state *ps, struct cursor *val, u64 *seed)
{
	struct cursor tok, extra;
	const char *p;
	u64 v = 0;
	bool hex = false;

	if (!next_token(val, &tok))
		return fail(ps, "seed: missing value", NULL, NULL);
	if (next_token(val, &extra))
		return fail(ps, "seed: too many values", NULL, NULL);
	p = tok.p;
	if (tok.end - p > 2 && p[0] == '0' && (p[1] == 'x' || p[1] == 'X')) {
		hex = true;
		p += 2;
	}
	for (; p < tok.end; p++) {
		int d = hex ? hex_val(*p) : (is_digit(*p) ? *p - '0' : -1);

		if (d < 0)
			return fail(ps, "seed: malformed number", &tok, NULL);
		if (hex) {
			if (v >> 60)
				return fail(ps, "seed", &tok, " out of range");
			v = v * 16 + d;
		} else {
			if (v > div64_u64(~0ULL - d, 10))
				return fail(ps, "seed", &tok, " out of range");
			v = v * 10 + d;
		}
	}
	*seed = v;
	return 0;
}

static int parse_faults(struct parse_state *ps, struct cursor *val, u32 *out)
{
	struct cursor tok;
	u32 faults = 0;
	bool any = false, none = false;
	int i;

	while (next_token(val, &tok)) {
		any = true;
		if (tok_eq(&tok, "none")) {
			none = true;
			continue;
		}
		for (i = 0; i < AS9888_FAULT_COUNT; i++)
			if (tok_eq(&tok, fault_names[i]))
				break;
		if (i == AS9888_FAULT_COUNT)
			return fail(ps, "unknown fault", &tok, NULL);
		faults |= BIT(i);
	}
	if (!any)
		return fail(ps, "fault: missing value", NULL, NULL);
	if (none && faults)
		return fail(ps, "fault: 'none' combined with faults", NULL,
			    NULL);
	*out = faults;
	return 0;
}

enum unit_key {
	KEY_EEPROM, KEY_OFFSET, KEY_UP, KEY_TEMPERATURE, KEY_DRIFT, KEY_NOISE,
	KEY_FIELD, KEY_SEED, KEY_FAULT, KEY_EARTH, KEY_HEADING,
	KEY_ORIENTATION, KEY_HARD_IRON, KEY_SOFT_IRON, KEY_MAGN_NOISE,
	KEY_DISTURBANCE, KEY_TUMBLE, KEY_COUNT,
};

static const char *const key_names[KEY_COUNT] = {
	"eeprom", "offset", "up", "temperature", "temperature_drift",
	"noise", "field", "seed", "fault", "earth", "heading", "orientation",
	"hard_iron", "soft_iron", "magn_noise", "disturbance", "tumble",
};

/* Keys that cannot be combined: each pair names one conflict */
static const u8 key_conflicts[][2] = {
	{ KEY_ORIENTATION, KEY_UP },
	{ KEY_ORIENTATION, KEY_HEADING },
	{ KEY_EARTH, KEY_FIELD },
};

/* One value in [lo, hi], @decimals places, into @out */
static int parse_ranged(struct parse_state *ps, struct cursor *val,
			int decimals, s64 lo, s64 hi, const char *what,
			s64 *out)
{
	s64 max = hi > -lo ? hi : -lo;
	int ret = parse_vector(ps, val, 1, decimals, max, what, out);

	if (ret)
		return ret;
	if (*out < lo || *out > hi)
		return fail(ps, what, NULL, " out of range");
	return 0;
}

/* "F I D": magnitude, inclination, declination */
static int parse_earth(struct parse_state *ps, struct cursor *val,
		       struct as9888_unit *u)
{
	s64 v[AS9888_UNIT_AXES];
	int ret;

	ret = parse_vector(ps, val, 3, 3, AS9888_UNIT_EARTH_MAX_NT, "earth",
			   v);
	if (ret)
		return ret;
	if (v[0] < 0 || v[0] > AS9888_UNIT_EARTH_MAX_NT)
		return fail(ps, "earth: magnitude", NULL,
			    " out of range (0..200 uT)");
	if (v[1] < -AS9888_UNIT_INCL_MAX_MDEG ||
	    v[1] > AS9888_UNIT_INCL_MAX_MDEG)
		return fail(ps, "earth: inclination", NULL,
			    " out of range (-90..90)");
	if (v[2] < -AS9888_UNIT_DECL_MAX_MDEG ||
	    v[2] > AS9888_UNIT_DECL_MAX_MDEG)
		return fail(ps, "earth: declination", NULL,
			    " out of range (-180..180)");
	u->earth_nt = (s32)v[0];
	u->incl_mdeg = (s32)v[1];
	u->decl_mdeg = (s32)v[2];
	u->world |= AS9888_UNIT_WORLD_EARTH;
	return 0;
}

static int parse_orientation(struct parse_state *ps, struct cursor *val,
			     struct as9888_unit *u)
{
	s64 v[4];
	int i, ret;

	ret = parse_vector(ps, val, 4, 6, AS9888_UNIT_ORIENT_MAX,
			   "orientation", v);
	if (ret)
		return ret;
	if (!v[0] && !v[1] && !v[2] && !v[3])
		return fail(ps, "orientation: zero quaternion", NULL, NULL);
	for (i = 0; i < 4; i++)
		u->orientation[i] = (s32)v[i];
	u->world |= AS9888_UNIT_WORLD_ORIENTATION;
	return 0;
}

/* "x y z n": peak field and length of a passing magnet */
static int parse_disturbance(struct parse_state *ps, struct cursor *val,
			     struct as9888_unit *u)
{
	struct cursor tok;
	s64 v[AS9888_UNIT_AXES], n;
	int i, ret;

	for (i = 0; i < AS9888_UNIT_AXES; i++) {
		if (!next_token(val, &tok))
			return fail(ps, "disturbance", NULL,
				    ": too few values");
		ret = parse_decimal(ps, &tok, 3, AS9888_UNIT_IRON_MAX_NT,
				    "disturbance", &v[i]);
		if (ret)
			return ret;
	}
	ret = parse_ranged(ps, val, 0, 0, AS9888_UNIT_DIST_MAX_SAMPLES,
			   "disturbance: length", &n);
	if (ret)
		return ret;
	for (i = 0; i < AS9888_UNIT_AXES; i++)
		u->dist_nt[i] = (s32)v[i];
	u->dist_samples = (u32)n;
	return 0;
}

/* The keys of the magnetic world (see as9888_unit.h) */
static int parse_world(struct parse_state *ps, int key, struct cursor *val,
		       struct as9888_unit *u)
{
	s64 v[AS9888_UNIT_AXES * AS9888_UNIT_AXES];
	int i, ret;

	switch (key) {
	case KEY_EARTH:
		return parse_earth(ps, val, u);
	case KEY_HEADING:
		ret = parse_ranged(ps, val, 3, -AS9888_UNIT_HEADING_MAX_MDEG,
				   AS9888_UNIT_HEADING_MAX_MDEG, "heading", v);
		if (!ret)
			u->heading_mdeg = (s32)v[0];
		return ret;
	case KEY_ORIENTATION:
		return parse_orientation(ps, val, u);
	case KEY_HARD_IRON:
		ret = parse_vector(ps, val, 3, 3, AS9888_UNIT_IRON_MAX_NT,
				   "hard_iron", v);
		for (i = 0; !ret && i < AS9888_UNIT_AXES; i++)
			u->hard_nt[i] = (s32)v[i];
		return ret;
	case KEY_SOFT_IRON:
		ret = parse_vector(ps, val, 9, 6, AS9888_UNIT_SOFT_MAX,
				   "soft_iron", v);
		for (i = 0; !ret && i < 9; i++)
			u->soft_ppm[i] = (s32)v[i];
		return ret;
	case KEY_MAGN_NOISE:
		ret = parse_ranged(ps, val, 3, 0, AS9888_UNIT_MNOISE_MAX_NT,
				   "magn_noise", v);
		if (!ret)
			u->magn_noise_nt = (u32)v[0];
		return ret;
	case KEY_DISTURBANCE:
		return parse_disturbance(ps, val, u);
	case KEY_TUMBLE:
		ret = parse_ranged(ps, val, 3, 0, AS9888_UNIT_TUMBLE_MAX_MDEG,
				   "tumble", v);
		if (!ret)
			u->tumble_mdeg = (u32)v[0];
		return ret;
	default:
		return -EINVAL;
	}
}

static int parse_value(struct parse_state *ps, int key, struct cursor *val,
		       struct as9888_unit *u)
{
	s64 v[AS9888_UNIT_AXES];
	s32 up[AS9888_UNIT_AXES];
	int i, ret;

	switch (key) {
	case KEY_EEPROM:
		return parse_eeprom(ps, val, u);
	case KEY_OFFSET:
		ret = parse_vector(ps, val, 3, 3, AS9888_UNIT_OFFSET_MAX_MLSB,
				   "offset", v);
		if (ret)
			return ret;
		for (i = 0; i < AS9888_UNIT_AXES; i++)
			u->offset_mlsb[i] = (s32)v[i];
		return 0;
	case KEY_UP:
		ret = parse_vector(ps, val, 3, 6, 1000000000LL, "up", v);
		if (ret)
			return ret;
		for (i = 0; i < AS9888_UNIT_AXES; i++)
			up[i] = (s32)v[i];
		if (as9888_unit_normalise(up, u->up))
			return fail(ps, "up: zero vector", NULL, NULL);
		return 0;
	case KEY_TEMPERATURE:
		ret = parse_vector(ps, val, 1, 3, 150000, "temperature", v);
		if (ret)
			return ret;
		if (v[0] < AS9888_UNIT_TEMP_MIN_MDEGC)
			return fail(ps, "temperature", NULL,
				    " out of range (-50..150)");
		u->temperature_mdegc = (s32)v[0];
		return 0;
	case KEY_DRIFT:
		ret = parse_vector(ps, val, 1, 6,
				   AS9888_UNIT_DRIFT_MAX_UDEGC_S,
				   "temperature_drift", v);
		if (ret)
			return ret;
		u->drift_udegc_s = (s32)v[0];
		return 0;
	case KEY_NOISE:
		ret = parse_vector(ps, val, 1, 3, AS9888_UNIT_NOISE_MAX_MLSB,
				   "noise", v);
		if (ret)
			return ret;
		if (v[0] < 0)
			return fail(ps, "noise", NULL, " must not be negative");
		u->noise_mlsb = (u32)v[0];
		return 0;
	case KEY_FIELD:
		ret = parse_vector(ps, val, 3, 3, AS9888_UNIT_FIELD_MAX_NT,
				   "field", v);
		if (ret)
			return ret;
		for (i = 0; i < AS9888_UNIT_AXES; i++)
			u->field_nt[i] = (s32)v[i];
		return 0;
	case KEY_SEED:
		return parse_seed(ps, val, &u->seed);
	case KEY_FAULT:
		return parse_faults(ps, val, &u->faults);
	default:
		return parse_world(ps, key, val, u);
	}
}

static int parse_line(struct parse_state *ps, const char *p, const char *end,
		      struct as9888_unit *u, u32 *seen)
{
	struct cursor key, val;
	const char *q;
	unsigned int i;
	int k;

	/* strip the comment */
	for (q = p; q < end; q++)
		if (*q == '#')
			break;
	end = q;
	while (p < end && is_space(*p))
		p++;
	while (end > p && is_space(end[-1]))
		end--;
	if (p == end)
		return 0;

	for (q = p; q < end && *q != '='; q++)
		;
	if (q == end) {
		key.p = p;
		key.end = end;
		return fail(ps, "expected 'key = value', got", &key, NULL);
	}
	key.p = p;
	key.end = q;
	while (key.end > key.p && is_space(key.end[-1]))
		key.end--;
	val.p = q + 1;
	val.end = end;
	while (val.p < val.end && is_space(*val.p))
		val.p++;
	if (key.p == key.end)
		return fail(ps, "missing key before '='", NULL, NULL);

	for (k = 0; k < KEY_COUNT; k++)
		if (tok_eq(&key, key_names[k]))
			break;
	if (k == KEY_COUNT)
		return fail(ps, "unknown key", &key, NULL);
	if (*seen & BIT(k))
		return fail(ps, "duplicate key", &key, NULL);
	*seen |= BIT(k);
	for (i = 0; i < ARRAY_SIZE(key_conflicts); i++)
		if ((*seen & BIT(key_conflicts[i][0])) &&
		    (*seen & BIT(key_conflicts[i][1])))
			return fail(ps, key_names[key_conflicts[i][0]], NULL,
				    key_conflicts[i][1] == KEY_FIELD ?
				    ": not with 'field'" :
				    ": not with 'up' or 'heading'");
	if (val.p == val.end)
		return fail(ps, "missing value for", &key, NULL);
	return parse_value(ps, k, &val, u);
}

int as9888_unit_parse(const char *text, unsigned int len,
		      struct as9888_unit *u, struct as9888_unit_error *err)
{
	struct parse_state ps = { .err = err, .line = 0 };
	const char *p, *end;
	u32 seen = 0;
	int ret;

	ps.mb.buf = err ? err->msg : ps.scratch;
	ps.mb.pos = 0;
	ps.mb.buf[0] = '\0';
	if (err)
		err->line = 0;
	as9888_unit_default(u);
	if (!text)
		return len ? fail(&ps, "no text", NULL, NULL) : 0;
	p = text;
	end = text + len;

	while (p < end) {
		const char *eol = p;

		while (eol < end && *eol != '\n')
			eol++;
		ps.line++;
		ret = parse_line(&ps, p, eol, u, &seen);
		if (ret)
			return ret;
		p = eol < end ? eol + 1 : eol;
	}
	return 0;
}
