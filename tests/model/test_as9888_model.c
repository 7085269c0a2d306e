// SPDX-License-Identifier: GPL-2.0
/*
 * Conformance tests of the AS9888 chip model against the datasheet: one
 * test per rule. Virtual time: T is advanced explicitly. The accelerometer
 * and magnetometer references are computed here in double precision from
 * the datasheet formulas, independently of the model's fixed point.
 */

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include <linux/errno.h>

#include "as9888_model.h"
#include "as9888_unit.h"

#define US	1000ULL
#define MSEC	1000000ULL

static struct as9888_model M;
static u64 T;

static void at(u64 ns)
{
	T += ns;
}

static u8 rd(u8 reg)
{
	u8 v = 0xa5;

	assert_int_equal(as9888_model_read(&M, T, reg, &v, 1), 0);
	return v;
}

static void rdn(u8 reg, u8 *buf, unsigned int len)
{
	assert_int_equal(as9888_model_read(&M, T, reg, buf, len), 0);
}

static void wr(u8 reg, u8 v)
{
	assert_int_equal(as9888_model_write(&M, T, reg, &v, 1), 0);
}

static void wrn(u8 reg, const u8 *buf, unsigned int len)
{
	assert_int_equal(as9888_model_write(&M, T, reg, buf, len), 0);
}

static bool pin1(void)
{
	return as9888_model_pin(&M, T, AS9888_PIN_INT1);
}

static bool pin2(void)
{
	return as9888_model_pin(&M, T, AS9888_PIN_INT2);
}

/* Power on with @u at T = 5 ms and wait t_BOOT. */
static void boot(const struct as9888_unit *u)
{
	T = 5 * MSEC;
	as9888_model_init(&M, u, T);
	at(AS9888_T_BOOT_NS);
}

/* Step 1 of the application note: EEPROM to the trim registers. */
static void load_trim_from(const u8 ee[21])
{
	u8 trim[10] = {
		ee[0], ee[1], 0x18 | (ee[2] & 7), ee[3],
		ee[7] & 0x7f, ee[8] & 0x7f, ee[9] & 0x7f,
		ee[13], ee[14], ee[15],
	};

	wrn(AS9888_REG_REF1, trim, sizeof(trim));
}

static void load_trim(void)
{
	u8 ee[21];

	wr(AS9888_REG_MS, AS9888_MS_EEPROM);
	at(AS9888_T_EEP_NS);
	rdn(AS9888_REG_EEPROM, ee, sizeof(ee));
	wr(AS9888_REG_MS, AS9888_MS_POWER_DOWN);
	at(AS9888_T_PD_NS);
	load_trim_from(ee);
}

static void ready(const struct as9888_unit *u)
{
	boot(u);
	load_trim();
}

static struct as9888_unit unit_default(void)
{
	struct as9888_unit u;

	as9888_unit_default(&u);
	return u;
}

struct sample {
	u8 st1;
	s16 h[3];
	u8 tmps;
	u8 empt;
	s16 a[3];
	u8 st2;
};

static s16 le16(const u8 *p)
{
	return (s16)(p[0] | p[1] << 8);
}

static void read_sample(struct sample *s)
{
	u8 b[16];
	int i;

	rdn(AS9888_REG_ST1, b, sizeof(b));
	s->st1 = b[0];
	for (i = 0; i < 3; i++) {
		s->h[i] = le16(&b[1 + 2 * i]);
		s->a[i] = le16(&b[9 + 2 * i]);
	}
	s->tmps = b[7];
	s->empt = b[8];
	s->st2 = b[15];
}

static u64 duration(u8 slct2, u8 mode)
{
	if (mode == AS9888_MS_SELF_TEST || (slct2 & AS9888_SLCT2_MEN_MSK))
		return AS9888_T_MAG_NS;
	return (slct2 & AS9888_SLCT2_ALPF_MSK) ? AS9888_T_ACC_LPF_NS :
					     AS9888_T_ACC_NS;
}

/* Wait t_PD, start @mode, wait for the end, read the burst. */
static void measure_mode(u8 slct2, u8 mode, struct sample *s)
{
	at(AS9888_T_PD_NS);
	wr(AS9888_REG_SLCT2, slct2);
	wr(AS9888_REG_MS, mode);
	assert_int_equal(rd(AS9888_REG_MS), mode);
	at(duration(slct2, mode));
	assert_int_equal(rd(AS9888_REG_MS), 0);
	read_sample(s);
}

static void measure(u8 slct2, struct sample *s)
{
	measure_mode(slct2, AS9888_MS_SINGLE, s);
}

/* ---- double-precision reference of datasheet sections 5, 6, 8 ---- */

static int s5(int v)
{
	return (v & 0x10) ? (v & 0x1f) - 32 : (v & 0x1f);
}

static int s9(int v)
{
	return (v & 0x100) ? (v & 0x1ff) - 512 : (v & 0x1ff);
}

static int ref_dac2lin(int ga, int da)
{
	int lin = da >= 0x80 ? da - 0x80 : -da;

	return (ga & 0x40) ? -lin : lin;
}

static double ref_kote(const u8 *ee, int axis)
{
	int et1 = ee[19], et2 = ee[20];
	double dT = (et1 - et2) / 1.6;
	int dt9 = s9(((ee[7 + axis] >> 7) << 8) | ee[10 + axis]);

	if (et1 < 0x28 || et1 > 0xe0 || et2 < 0x28 || et2 > 0xe0 ||
	    dT < 10 || dT > 80)
		dT = 35;
	return dt9 * 1.5 / dT;
}

static double ref_accel(const struct as9888_unit *u, int axis, u8 aga, u8 ada,
			double t)
{
	const u8 *ee = u->eeprom;
	int ega = ee[7 + axis], gtd = ee[16 + axis];
	double t_rt = (176 - (136 + s5(ee[2] >> 3))) / 1.6;
	double kste = -0.428125 + 0.04375 * (gtd >> 5);
	double st = (256 + s5(gtd & 0x1f)) * (1 + kste / 100 * (t - t_rt));
	double kgain = ((aga & 63) + 16.0) / ((ega & 63) + 16.0);
	double o = u->offset_mlsb[axis] / 1000.0 +
		   ref_kote(ee, axis) * (t - 25) +
		   (ref_dac2lin(aga, ada) - ref_dac2lin(ega, ee[13 + axis])) *
		   2048.0 / ((aga & 63) + 16);

	return st * kgain * u->up[axis] / 1e6 + o;
}

/* raw must be clamp(rint(v)); near a tie either neighbour is accepted */
static void expect_raw(double v, s16 raw, double lo, double hi)
{
	double r = rint(v);

	if (fabs(fabs(v - floor(v)) - 0.5) < 1e-6) {
		assert_true(raw == (s16)fmin(fmax(floor(v), lo), hi) ||
			    raw == (s16)fmin(fmax(ceil(v), lo), hi));
		return;
	}
	assert_int_equal(raw, (s16)fmin(fmax(r, lo), hi));
}

static double ref_mag(const struct as9888_unit *u, int axis, double gen_adj)
{
	double ehc = u->eeprom[4 + axis];

	return (u->field_nt[axis] / 1000.0 / 0.3 + gen_adj) * 256 /
	       (ehc + 128);
}

/* ---- registers ---- */

/* The shared register header against the datasheet, literally. */
static void test_register_addresses(void **state)
{
	assert_int_equal(AS9888_REG_WIA, 0x00);
	assert_int_equal(AS9888_WIA_VAL, 0x48);
	assert_int_equal(AS9888_REG_INT1EN, 0x02);
	assert_int_equal(AS9888_REG_INT2EN, 0x03);
	assert_int_equal(AS9888_REG_INT1ST, 0x04);
	assert_int_equal(AS9888_REG_INT2ST, 0x05);
	assert_int_equal(AS9888_REG_SLCT1, 0x06);
	assert_int_equal(AS9888_REG_SLCT2, 0x07);
	assert_int_equal(AS9888_REG_MS, 0x08);
	assert_int_equal(AS9888_REG_ST1, 0x10);
	assert_int_equal(AS9888_REG_HXL, 0x11);
	assert_int_equal(AS9888_REG_TMPS, 0x17);
	assert_int_equal(AS9888_REG_EMPT, 0x18);
	assert_int_equal(AS9888_REG_A1XL, 0x19);
	assert_int_equal(AS9888_REG_ST2, 0x1f);
	assert_int_equal(AS9888_REG_REF1, 0x30);
	assert_int_equal(AS9888_REG_REF3, 0x32);
	assert_int_equal(AS9888_REG_OSC, 0x33);
	assert_int_equal(AS9888_REG_AXGA, 0x34);
	assert_int_equal(AS9888_REG_AXDA, 0x37);
	assert_int_equal(AS9888_REG_AZDA, 0x39);
	assert_int_equal(AS9888_REG_EEPROM, 0x40);
	assert_int_equal(AS9888_REG_EEPROM_END, 0x54);
	assert_int_equal(AS9888_SLCT2_MEN_MSK, 0x04);
	assert_int_equal(AS9888_SLCT2_ALPF_MSK, 0x08);
	assert_int_equal(AS9888_ST1_DRDY_MSK, 0x01);
	assert_int_equal(AS9888_ST1_DOR_MSK, 0x02);
	assert_int_equal(AS9888_ST2_HST_MSK, 0x02);
	assert_int_equal(AS9888_ST2_HOFL_MSK, 0x08);
	assert_int_equal(AS9888_T_RSTL_NS, 5000);
	assert_int_equal(AS9888_T_BOOT_NS, 100000);
	assert_int_equal(AS9888_T_EEP_NS, 300000);
	assert_int_equal(AS9888_T_PD_NS, 100000);
	assert_int_equal(AS9888_T_ACC_NS, 1200000);
	assert_int_equal(AS9888_T_ACC_LPF_NS, 4800000);
	assert_int_equal(AS9888_T_MAG_NS, 7300000);
}

static void test_wia(void **state)
{
	boot(NULL);
	assert_int_equal(rd(AS9888_REG_WIA), 0x48);
	wr(AS9888_REG_WIA, 0x12);
	assert_int_equal(rd(AS9888_REG_WIA), 0x48);
}

static void test_reset_values(void **state)
{
	u8 b[10];
	int r;

	boot(NULL);
	for (r = AS9888_REG_INT1EN; r <= AS9888_REG_MS; r++)
		assert_int_equal(rd(r), 0);
	assert_int_equal(rd(AS9888_REG_ST1), 0);
	assert_int_equal(rd(AS9888_REG_EMPT), 0);
	rdn(AS9888_REG_REF1, b, 10);
	for (r = 0; r < 7; r++)
		assert_int_equal(b[r], 0);
	for (r = 7; r < 10; r++)
		assert_int_equal(b[r], 0x80);
}

static void test_rw_registers(void **state)
{
	static const u8 regs[] = {
		AS9888_REG_INT1EN, AS9888_REG_INT2EN, AS9888_REG_SLCT1,
		AS9888_REG_SLCT2,
	};
	unsigned int i;

	boot(NULL);
	for (i = 0; i < sizeof(regs); i++) {
		wr(regs[i], 0x5a + i);
		assert_int_equal(rd(regs[i]), 0x5a + i);
		wr(regs[i], 0);
		assert_int_equal(rd(regs[i]), 0);
	}
}

static void test_unlisted_registers(void **state)
{
	int r;

	boot(NULL);
	for (r = 0; r < 256; r++) {
		bool listed = r == 0 || (r >= 2 && r <= 8) ||
			      (r >= 0x10 && r <= 0x1f) ||
			      (r >= 0x30 && r <= 0x39) ||
			      (r >= 0x40 && r <= 0x54);

		if (listed)
			continue;
		wr(r, 0xff);
		assert_int_equal(rd(r), 0);
	}
	/* writing the unlisted ones changed nothing listed */
	assert_int_equal(rd(AS9888_REG_INT1EN), 0);
	assert_int_equal(rd(AS9888_REG_MS), 0);
	assert_int_equal(rd(AS9888_REG_AXDA), 0x80);
}

static void test_readonly_registers(void **state)
{
	struct sample s;
	u8 b[15];
	int r, i;

	ready(NULL);
	wr(AS9888_REG_INT1EN, 1);
	measure(AS9888_SLCT2_MEN_MSK, &s);
	for (r = AS9888_REG_ST1; r <= AS9888_REG_ST2; r++)
		wr(r, 0x77);
	wr(AS9888_REG_INT1ST, 0);
	wr(AS9888_REG_INT2ST, 1);
	assert_true(pin1());
	assert_false(pin2());
	assert_int_equal(rd(AS9888_REG_ST1), 0);
	rdn(AS9888_REG_HXL, b, 15);
	for (i = 0; i < 3; i++) {
		assert_int_equal(le16(&b[2 * i]), s.h[i]);
		assert_int_equal(le16(&b[8 + 2 * i]), s.a[i]);
	}
	assert_int_equal(b[6], s.tmps);
	assert_int_equal(b[7], 0);
	assert_int_equal(b[14], s.st2);
}

static void test_empt_zero(void **state)
{
	struct sample s;

	ready(NULL);
	measure(AS9888_SLCT2_MEN_MSK, &s);
	assert_int_equal(s.empt, 0);
	assert_int_equal(rd(AS9888_REG_EMPT), 0);
}

/* ---- modes ---- */

static void test_mode_single(void **state)
{
	boot(NULL);
	wr(AS9888_REG_MS, AS9888_MS_SINGLE);
	assert_int_equal(rd(AS9888_REG_MS), AS9888_MS_SINGLE);
	at(AS9888_T_ACC_NS - 1);
	assert_int_equal(rd(AS9888_REG_MS), AS9888_MS_SINGLE);
	at(1);
	assert_int_equal(rd(AS9888_REG_MS), AS9888_MS_POWER_DOWN);
	assert_int_equal(rd(AS9888_REG_ST1) & AS9888_ST1_DRDY_MSK,
			 AS9888_ST1_DRDY_MSK);
}

static void test_mode_eeprom_enter_leave(void **state)
{
	boot(NULL);
	wr(AS9888_REG_MS, AS9888_MS_EEPROM);
	assert_int_equal(rd(AS9888_REG_MS), AS9888_MS_EEPROM);
	at(10 * MSEC);
	/* stays until 0 is written; other modes ignored */
	wr(AS9888_REG_MS, AS9888_MS_SINGLE);
	assert_int_equal(rd(AS9888_REG_MS), AS9888_MS_EEPROM);
	wr(AS9888_REG_MS, AS9888_MS_SELF_TEST);
	assert_int_equal(rd(AS9888_REG_MS), AS9888_MS_EEPROM);
	at(10 * MSEC);
	assert_int_equal(rd(AS9888_REG_MS), AS9888_MS_EEPROM);
	wr(AS9888_REG_MS, AS9888_MS_POWER_DOWN);
	assert_int_equal(rd(AS9888_REG_MS), AS9888_MS_POWER_DOWN);
}

static void test_mode_self_test(void **state)
{
	boot(NULL);
	wr(AS9888_REG_MS, AS9888_MS_SELF_TEST);
	assert_int_equal(rd(AS9888_REG_MS), AS9888_MS_SELF_TEST);
	at(AS9888_T_MAG_NS - 1);
	assert_int_equal(rd(AS9888_REG_MS), AS9888_MS_SELF_TEST);
	at(1);
	assert_int_equal(rd(AS9888_REG_MS), 0);
	assert_int_equal(rd(AS9888_REG_ST1) & AS9888_ST1_DRDY_MSK, 1);
}

static void test_mode_ignored_not_from_pd(void **state)
{
	boot(NULL);
	wr(AS9888_REG_MS, AS9888_MS_SINGLE);
	at(100 * US);
	wr(AS9888_REG_MS, AS9888_MS_EEPROM);
	wr(AS9888_REG_MS, AS9888_MS_SELF_TEST);
	assert_int_equal(rd(AS9888_REG_MS), AS9888_MS_SINGLE);
	/* the running measurement is not restarted nor lengthened */
	at(AS9888_T_ACC_NS - 100 * US);
	assert_int_equal(rd(AS9888_REG_MS), 0);
	assert_int_equal(M.stats.measurements, 1);
}

static void test_mode_ignored_before_tpd(void **state)
{
	boot(NULL);
	wr(AS9888_REG_MS, AS9888_MS_EEPROM);
	at(50 * US);
	wr(AS9888_REG_MS, 0);
	at(AS9888_T_PD_NS - 1);
	wr(AS9888_REG_MS, AS9888_MS_SINGLE);
	assert_int_equal(rd(AS9888_REG_MS), 0);
	at(1);
	wr(AS9888_REG_MS, AS9888_MS_SINGLE);
	assert_int_equal(rd(AS9888_REG_MS), AS9888_MS_SINGLE);
}

static void test_mode_ignored_before_tpd_after_auto_return(void **state)
{
	boot(NULL);
	wr(AS9888_REG_MS, AS9888_MS_SINGLE);
	at(AS9888_T_ACC_NS + AS9888_T_PD_NS - 1);
	wr(AS9888_REG_MS, AS9888_MS_EEPROM);
	assert_int_equal(rd(AS9888_REG_MS), 0);
	at(1);
	wr(AS9888_REG_MS, AS9888_MS_EEPROM);
	assert_int_equal(rd(AS9888_REG_MS), AS9888_MS_EEPROM);
}

static void test_mode_power_on_entry_tpd(void **state)
{
	/* power-down is entered at power-on: MS accepted right after boot */
	boot(NULL);
	wr(AS9888_REG_MS, AS9888_MS_EEPROM);
	assert_int_equal(rd(AS9888_REG_MS), AS9888_MS_EEPROM);
}

static void test_mode_reserved_ignored(void **state)
{
	int v;

	ready(NULL);
	wr(AS9888_REG_INT1EN, 1);
	wr(AS9888_REG_MS, AS9888_MS_SINGLE);
	at(AS9888_T_ACC_NS + AS9888_T_PD_NS);
	assert_true(pin1());
	for (v = 1; v < 256; v++) {
		if (v == 1 || v == 4 || v == 8)
			continue;
		wr(AS9888_REG_MS, v);
		assert_int_equal(rd(AS9888_REG_MS), 0);
	}
	assert_int_equal(M.stats.measurements, 1);
	assert_true(pin1());
	assert_int_equal(rd(AS9888_REG_ST1), AS9888_ST1_DRDY_MSK);
}

static void test_mode_ignored_write_changes_nothing(void **state)
{
	ready(NULL);
	wr(AS9888_REG_INT1EN, 1);
	wr(AS9888_REG_INT2EN, 1);
	wr(AS9888_REG_MS, AS9888_MS_SINGLE);
	at(AS9888_T_ACC_NS);
	/* before t_PD after the automatic return: ignored */
	wr(AS9888_REG_MS, AS9888_MS_SINGLE);
	assert_true(pin1());
	assert_true(pin2());
	assert_int_equal(rd(AS9888_REG_ST1), AS9888_ST1_DRDY_MSK);
	assert_int_equal(rd(AS9888_REG_MS), 0);
	/* and the ignored write did not restart the t_PD timer */
	at(AS9888_T_PD_NS);
	wr(AS9888_REG_MS, AS9888_MS_SINGLE);
	assert_int_equal(rd(AS9888_REG_MS), AS9888_MS_SINGLE);
}

static void test_mode_zero_aborts(void **state)
{
	boot(NULL);
	wr(AS9888_REG_INT1EN, 1);
	wr(AS9888_REG_MS, AS9888_MS_SINGLE);
	at(AS9888_T_ACC_NS / 2);
	wr(AS9888_REG_MS, 0);
	assert_int_equal(rd(AS9888_REG_MS), 0);
	at(20 * MSEC);
	assert_int_equal(rd(AS9888_REG_ST1), 0);
	assert_false(pin1());
	assert_int_equal(M.stats.measurements, 0);
	assert_int_equal(M.stats.aborted, 1);
	assert_int_equal(as9888_model_next_event_ns(&M), U64_MAX);
}

static void test_mode_zero_abort_starts_tpd(void **state)
{
	boot(NULL);
	wr(AS9888_REG_MS, AS9888_MS_SELF_TEST);
	at(1 * MSEC);
	wr(AS9888_REG_MS, 0);
	at(AS9888_T_PD_NS - 1);
	wr(AS9888_REG_MS, AS9888_MS_SINGLE);
	assert_int_equal(rd(AS9888_REG_MS), 0);
	at(1);
	wr(AS9888_REG_MS, AS9888_MS_SINGLE);
	assert_int_equal(rd(AS9888_REG_MS), AS9888_MS_SINGLE);
}

static void test_mode_accepted_write_deasserts(void **state)
{
	ready(NULL);
	wr(AS9888_REG_INT1EN, 1);
	wr(AS9888_REG_INT2EN, 1);
	wr(AS9888_REG_MS, AS9888_MS_SINGLE);
	at(AS9888_T_ACC_NS + AS9888_T_PD_NS);
	assert_true(pin1());
	assert_true(pin2());
	wr(AS9888_REG_MS, AS9888_MS_SINGLE);
	assert_false(pin1());
	assert_false(pin2());
	assert_int_equal(rd(AS9888_REG_ST1) & AS9888_ST1_DRDY_MSK, 0);
	assert_int_equal(rd(AS9888_REG_INT1ST), 0);
	assert_int_equal(rd(AS9888_REG_INT2ST), 0);
}

static void test_mode_zero_in_pd_deasserts(void **state)
{
	ready(NULL);
	wr(AS9888_REG_INT1EN, 1);
	wr(AS9888_REG_MS, AS9888_MS_SINGLE);
	at(AS9888_T_ACC_NS + 10 * US);
	assert_true(pin1());
	wr(AS9888_REG_MS, 0);
	assert_false(pin1());
	assert_int_equal(rd(AS9888_REG_ST1), 0);
	/* t_PD still counts from the automatic return */
	at(AS9888_T_PD_NS - 10 * US);
	wr(AS9888_REG_MS, AS9888_MS_SINGLE);
	assert_int_equal(rd(AS9888_REG_MS), AS9888_MS_SINGLE);
}

/* ---- INT pins ---- */

static void int_case(u8 en1, u8 en2)
{
	ready(NULL);
	wr(AS9888_REG_INT1EN, en1);
	wr(AS9888_REG_INT2EN, en2);
	wr(AS9888_REG_MS, AS9888_MS_SINGLE);
	at(AS9888_T_ACC_NS - 1);
	assert_false(pin1());
	assert_false(pin2());
	at(1);
	assert_int_equal(pin1(), en1 & 1);
	assert_int_equal(pin2(), en2 & 1);
	assert_int_equal(rd(AS9888_REG_ST1) & 1, 1);
}

static void test_int_rise_enabled(void **state)
{
	int_case(1, 0);
	int_case(0, 1);
	int_case(1, 1);
	int_case(0, 0);
	int_case(0xfe, 0xfe);	/* only bit 0 enables */
}

static void test_intst_read_deasserts(void **state)
{
	ready(NULL);
	wr(AS9888_REG_INT1EN, 1);
	wr(AS9888_REG_INT2EN, 1);
	wr(AS9888_REG_MS, AS9888_MS_SINGLE);
	at(AS9888_T_ACC_NS);
	assert_true(pin1());
	assert_int_equal(rd(AS9888_REG_INT1ST), 1);
	assert_false(pin1());
	assert_true(pin2());
	assert_int_equal(rd(AS9888_REG_INT1ST), 0);
	assert_int_equal(rd(AS9888_REG_INT2ST), 1);
	assert_false(pin2());
	assert_int_equal(rd(AS9888_REG_INT2ST), 0);
	/* DRDY is independent of INTxST */
	assert_int_equal(rd(AS9888_REG_ST1), AS9888_ST1_DRDY_MSK);
}

static void test_int_stays_after_st2(void **state)
{
	struct sample s;

	ready(NULL);
	wr(AS9888_REG_INT1EN, 1);
	measure(0, &s);
	/* reading the data (ST2) does not move the pin */
	assert_true(pin1());
	assert_int_equal(rd(AS9888_REG_ST1), 0);
}

/* ---- status ---- */

static void test_st2_clears_drdy_dor(void **state)
{
	ready(NULL);
	wr(AS9888_REG_MS, AS9888_MS_SINGLE);
	at(AS9888_T_ACC_NS + AS9888_T_PD_NS);
	wr(AS9888_REG_MS, AS9888_MS_SINGLE);	/* previous left unread */
	at(AS9888_T_ACC_NS);
	rd(AS9888_REG_HXL);
	rd(AS9888_REG_A1ZH);
	assert_int_equal(rd(AS9888_REG_ST1),
			 AS9888_ST1_DRDY_MSK | AS9888_ST1_DOR_MSK);
	rd(AS9888_REG_ST2);
	assert_int_equal(rd(AS9888_REG_ST1), 0);
}

static void test_dor(void **state)
{
	struct sample s;

	ready(NULL);
	wr(AS9888_REG_MS, AS9888_MS_SINGLE);
	at(AS9888_T_ACC_NS);
	/* data regs read but not ST2: still unread */
	rd(AS9888_REG_ST1);
	rd(AS9888_REG_A1XL);
	at(AS9888_T_PD_NS);
	wr(AS9888_REG_MS, AS9888_MS_SINGLE);
	assert_int_equal(rd(AS9888_REG_ST1), 0);	/* MS cleared DRDY */
	at(AS9888_T_ACC_NS);
	read_sample(&s);
	assert_int_equal(s.st1, AS9888_ST1_DRDY_MSK | AS9888_ST1_DOR_MSK);
	/* the ST2 read ended it: the next one is clean */
	measure(0, &s);
	assert_int_equal(s.st1, AS9888_ST1_DRDY_MSK);
}

static void test_dor_not_set_when_read(void **state)
{
	struct sample s;
	int i;

	ready(NULL);
	for (i = 0; i < 3; i++) {
		measure(0, &s);
		assert_int_equal(s.st1, AS9888_ST1_DRDY_MSK);
	}
}

static void test_hst(void **state)
{
	struct sample s;

	ready(NULL);
	measure(0, &s);
	assert_int_equal(s.st2, AS9888_ST2_HST_MSK);
	assert_int_equal(s.h[0], 0);
	assert_int_equal(s.h[1], 0);
	assert_int_equal(s.h[2], 0);
	measure(AS9888_SLCT2_MEN_MSK, &s);
	assert_int_equal(s.st2, 0);
	measure(AS9888_SLCT2_ALPF_MSK, &s);
	assert_int_equal(s.st2, AS9888_ST2_HST_MSK);
	measure_mode(0, AS9888_MS_SELF_TEST, &s);
	assert_int_equal(s.st2, 0);
}

static void test_hofl_saturation(void **state)
{
	struct as9888_unit u = unit_default();
	struct sample s;

	u.field_nt[1] = -2000000;	/* -2000 uT: beyond the range */
	ready(&u);
	measure(AS9888_SLCT2_MEN_MSK, &s);
	assert_int_equal(s.h[1], -4096);
	assert_int_equal(s.st2, AS9888_ST2_HOFL_MSK);
	u.field_nt[1] = 1300000;
	ready(&u);
	measure(AS9888_SLCT2_MEN_MSK, &s);
	assert_int_equal(s.h[1], 4095);
	assert_int_equal(s.st2, AS9888_ST2_HOFL_MSK);
	u.field_nt[1] = 1000000;	/* in range */
	ready(&u);
	measure(AS9888_SLCT2_MEN_MSK, &s);
	assert_true(s.h[1] < 4095);
	assert_int_equal(s.st2, 0);
}

/* ---- bursts ---- */

static void test_burst_read_sample(void **state)
{
	struct sample s;
	u8 single[14];
	int i;

	ready(NULL);
	wr(AS9888_REG_SLCT2, AS9888_SLCT2_MEN_MSK);
	wr(AS9888_REG_MS, AS9888_MS_SINGLE);
	at(AS9888_T_MAG_NS);
	for (i = 0; i < 14; i++)
		single[i] = rd(AS9888_REG_HXL + i);
	/* reading the data registers one by one does not end the read */
	assert_int_equal(rd(AS9888_REG_ST1), AS9888_ST1_DRDY_MSK);
	read_sample(&s);
	/* ST1 first in the burst still shows DRDY, ST2 at the end clears */
	assert_int_equal(s.st1, AS9888_ST1_DRDY_MSK);
	assert_int_equal(rd(AS9888_REG_ST1), 0);
	for (i = 0; i < 3; i++) {
		assert_int_equal(s.h[i], le16(&single[2 * i]));
		assert_int_equal(s.a[i], le16(&single[8 + 2 * i]));
	}
	assert_int_equal(s.tmps, single[6]);
	assert_int_equal(s.st2, rd(AS9888_REG_ST2));
	/* values are sign-extended little-endian: Z field is negative */
	assert_true(s.h[2] < 0);
	assert_int_equal(single[5], 0xff);
}

static void test_burst_write_auto_increment(void **state)
{
	u8 b[6] = { 1, 1, 0xee, 0xee, 0x33, AS9888_SLCT2_MEN_MSK };

	boot(NULL);
	wrn(AS9888_REG_INT1EN, b, 6);	/* INT1EN..SLCT2 */
	assert_int_equal(rd(AS9888_REG_INT1EN), 1);
	assert_int_equal(rd(AS9888_REG_INT2EN), 1);
	assert_int_equal(rd(AS9888_REG_INT1ST), 0);	/* read-only */
	assert_int_equal(rd(AS9888_REG_SLCT1), 0x33);
	assert_int_equal(rd(AS9888_REG_SLCT2), AS9888_SLCT2_MEN_MSK);
	/* a burst ending in MS starts a measurement with the new SLCT2 */
	{
		u8 c[2] = { 0, AS9888_MS_SINGLE };

		wrn(AS9888_REG_SLCT2, c, 2);
		assert_int_equal(rd(AS9888_REG_MS), AS9888_MS_SINGLE);
		at(AS9888_T_ACC_NS);
		assert_int_equal(rd(AS9888_REG_MS), 0);
	}
}

static void test_burst_read_auto_increment(void **state)
{
	u8 b[9];

	boot(NULL);
	wr(AS9888_REG_INT1EN, 1);
	wr(AS9888_REG_SLCT2, 0x0c);
	rdn(AS9888_REG_WIA, b, 9);
	assert_int_equal(b[0], 0x48);
	assert_int_equal(b[1], 0);
	assert_int_equal(b[2], 1);
	assert_int_equal(b[7], 0x0c);
	assert_int_equal(b[8], 0);
}

static void test_burst_crossing_regions(void **state)
{
	u8 b[0x56 - 0x38];
	int i;

	boot(NULL);
	/* 0x38..0x55: trim, unlisted 0x3a..0x3f, EEPROM (hidden), 0x55 */
	rdn(0x38, b, sizeof(b));
	assert_int_equal(b[0], 0x80);
	assert_int_equal(b[1], 0x80);
	for (i = 2; i < (int)sizeof(b); i++)
		assert_int_equal(b[i], 0);
	wr(AS9888_REG_MS, AS9888_MS_EEPROM);
	at(AS9888_T_EEP_NS);
	rdn(0x38, b, sizeof(b));
	for (i = 2; i < 8; i++)
		assert_int_equal(b[i], 0);
	for (i = 0; i < 21; i++)
		assert_int_equal(b[8 + i], M.unit.eeprom[i]);
	assert_int_equal(b[29], 0);
	/* a burst write across the EEPROM window changes nothing there */
	{
		u8 w[4] = { 1, 2, 3, 4 };

		wrn(0x3e, w, 4);
		assert_int_equal(rd(0x40), M.unit.eeprom[0]);
		assert_int_equal(rd(0x41), M.unit.eeprom[1]);
	}
}

static void test_burst_wraps(void **state)
{
	u8 b[2];

	boot(NULL);
	rdn(0xff, b, 2);
	assert_int_equal(b[0], 0);
	assert_int_equal(b[1], 0x48);	/* I2C: 0xff -> 0x00 */
	as9888_model_set_bus(&M, AS9888_BUS_SPI);
	rdn(0x7f, b, 2);
	assert_int_equal(b[1], 0x48);	/* SPI: 7-bit address */
}

static void test_burst_write_trim(void **state)
{
	u8 w[10] = { 1, 2, 0x1d, 4, 0x85, 0x86, 0xff, 0x10, 0x20, 0x30 };
	u8 b[10];

	boot(NULL);
	wrn(AS9888_REG_REF1, w, 10);
	rdn(AS9888_REG_REF1, b, 10);
	assert_int_equal(b[0], 1);
	assert_int_equal(b[2], 0x1d);
	assert_int_equal(b[4], 0x05);	/* AxGA bit 7 reads 0 */
	assert_int_equal(b[5], 0x06);
	assert_int_equal(b[6], 0x7f);
	assert_int_equal(b[7], 0x10);
	assert_int_equal(b[9], 0x30);
}

/* ---- trim registers ---- */

static void test_trim_only_in_pd(void **state)
{
	boot(NULL);
	wr(AS9888_REG_MS, AS9888_MS_EEPROM);
	wr(AS9888_REG_REF1, 0x11);
	wr(AS9888_REG_AXGA, 0x11);
	wr(AS9888_REG_AZDA, 0x11);
	wr(AS9888_REG_MS, 0);
	assert_int_equal(rd(AS9888_REG_REF1), 0);
	assert_int_equal(rd(AS9888_REG_AXGA), 0);
	assert_int_equal(rd(AS9888_REG_AZDA), 0x80);
	at(AS9888_T_PD_NS);
	wr(AS9888_REG_MS, AS9888_MS_SINGLE);
	wr(AS9888_REG_OSC, 0x22);
	at(AS9888_T_ACC_NS);
	assert_int_equal(rd(AS9888_REG_OSC), 0);
	wr(AS9888_REG_OSC, 0x22);
	assert_int_equal(rd(AS9888_REG_OSC), 0x22);
}

static void test_ga_bit7_reads_zero(void **state)
{
	int r;

	boot(NULL);
	for (r = AS9888_REG_AXGA; r < AS9888_REG_AXDA; r++) {
		wr(r, 0xff);
		assert_int_equal(rd(r), 0x7f);
		wr(r, 0x80);
		assert_int_equal(rd(r), 0);
	}
	/* the other trim registers keep all 8 bits */
	wr(AS9888_REG_AXDA, 0xff);
	assert_int_equal(rd(AS9888_REG_AXDA), 0xff);
	wr(AS9888_REG_REF2, 0xff);
	assert_int_equal(rd(AS9888_REG_REF2), 0xff);
}

/* ---- EEPROM ---- */

static void test_eeprom_hidden_before_teep(void **state)
{
	u8 b[21];
	int i;

	boot(NULL);
	wr(AS9888_REG_MS, AS9888_MS_EEPROM);
	at(AS9888_T_EEP_NS - 1);
	rdn(AS9888_REG_EEPROM, b, 21);
	for (i = 0; i < 21; i++)
		assert_int_equal(b[i], 0);
}

static void test_eeprom_visible_after_teep(void **state)
{
	static const u8 ex[21] = {
		0x9a, 0x71, 0x15, 0x5c, 0x80, 0x85, 0x7b, 0x1c, 0x63, 0xa2,
		0x38, 0xe6, 0x9c, 0x0d, 0x8f, 0x8c, 0x04, 0x65, 0xc3, 0x88,
		0x50,
	};
	u8 b[21];
	int i;

	boot(NULL);
	wr(AS9888_REG_MS, AS9888_MS_EEPROM);
	at(AS9888_T_EEP_NS);
	rdn(AS9888_REG_EEPROM, b, 21);
	assert_memory_equal(b, ex, 21);
	for (i = 0; i < 21; i++)
		assert_int_equal(rd(AS9888_REG_EEPROM + i), ex[i]);
}

static void test_eeprom_hidden_other_modes(void **state)
{
	int i;

	boot(NULL);
	for (i = 0x40; i <= 0x54; i++)
		assert_int_equal(rd(i), 0);	/* power-down */
	wr(AS9888_REG_MS, AS9888_MS_SINGLE);
	at(AS9888_T_EEP_NS);
	assert_int_equal(rd(AS9888_REG_MS), AS9888_MS_SINGLE);
	for (i = 0x40; i <= 0x54; i++)
		assert_int_equal(rd(i), 0);	/* measuring */
	at(10 * MSEC);
	wr(AS9888_REG_MS, AS9888_MS_SELF_TEST);
	at(AS9888_T_EEP_NS);
	for (i = 0x40; i <= 0x54; i++)
		assert_int_equal(rd(i), 0);	/* self-test */
	at(10 * MSEC);
	wr(AS9888_REG_MS, AS9888_MS_EEPROM);
	at(AS9888_T_EEP_NS);
	assert_int_equal(rd(0x40), 0x9a);
	wr(AS9888_REG_MS, 0);
	for (i = 0x40; i <= 0x54; i++)
		assert_int_equal(rd(i), 0);	/* left */
}

static void test_eeprom_teep_restarts(void **state)
{
	boot(NULL);
	wr(AS9888_REG_MS, AS9888_MS_EEPROM);
	at(AS9888_T_EEP_NS);
	assert_int_equal(rd(0x40), 0x9a);
	wr(AS9888_REG_MS, 0);
	at(AS9888_T_PD_NS);
	wr(AS9888_REG_MS, AS9888_MS_EEPROM);
	at(AS9888_T_EEP_NS - 1);
	assert_int_equal(rd(0x40), 0);
	at(1);
	assert_int_equal(rd(0x40), 0x9a);
}

/* ---- reset and boot ---- */

static void test_reset_pulse(void **state)
{
	ready(NULL);
	wr(AS9888_REG_INT1EN, 1);
	wr(AS9888_REG_SLCT2, AS9888_SLCT2_MEN_MSK);
	as9888_model_set_rstn(&M, T, false);
	at(AS9888_T_RSTL_NS);
	as9888_model_set_rstn(&M, T, true);
	at(AS9888_T_BOOT_NS);
	assert_int_equal(rd(AS9888_REG_INT1EN), 0);
	assert_int_equal(rd(AS9888_REG_SLCT2), 0);
	assert_int_equal(rd(AS9888_REG_REF1), 0);
	assert_int_equal(rd(AS9888_REG_AXGA), 0);
	assert_int_equal(rd(AS9888_REG_AXDA), 0x80);
	assert_int_equal(M.stats.resets, 1);
}

static void test_power_off_on(void **state)
{
	u8 v;
	s32 t0;

	ready(NULL);
	t0 = as9888_model_temperature_mdegc(&M, T);
	wr(AS9888_REG_INT1EN, 1);
	wr(AS9888_REG_SLCT2, AS9888_SLCT2_MEN_MSK);
	wr(AS9888_REG_MS, AS9888_MS_SINGLE);
	as9888_model_set_power(&M, T, false);
	assert_int_equal(M.stats.aborted, 1);
	assert_int_equal(M.stats.power_offs, 1);
	/* unpowered: no answer, pins low, no measurement ends */
	assert_int_equal(as9888_model_read(&M, T, 0, &v, 1), -EIO);
	at(AS9888_T_MAG_NS);
	assert_false(pin1());
	assert_int_equal(M.stats.measurements, 0);
	as9888_model_set_power(&M, T, true);
	at(AS9888_T_BOOT_NS - 1);
	assert_int_equal(as9888_model_read(&M, T, 0, &v, 1), -EIO);
	at(1);
	/* registers at their reset values, the unit's physics unchanged */
	assert_int_equal(rd(AS9888_REG_INT1EN), 0);
	assert_int_equal(rd(AS9888_REG_SLCT2), 0);
	assert_int_equal(rd(AS9888_REG_REF1), 0);
	assert_int_equal(rd(AS9888_REG_AXDA), 0x80);
	assert_int_equal(as9888_model_temperature_mdegc(&M, T), t0);
	assert_int_equal(M.stats.power_offs, 1);
}

/* A host that talks to, or drives RSTN into, a chip it switched off */
static void test_unpowered_access_counted(void **state)
{
	u8 v = 0;

	ready(NULL);
	/* RSTN high when the supply goes off: back-powering */
	as9888_model_set_power(&M, T, false);
	assert_int_equal(M.stats.backpowered, 1);
	assert_int_equal(as9888_model_read(&M, T, 0, &v, 1), -EIO);
	assert_int_equal(as9888_model_write(&M, T, AS9888_REG_MS, &v, 1), -EIO);
	assert_int_equal(M.stats.unpowered_transfers, 2);
	/* RSTN low, then high while still unpowered: once more */
	as9888_model_set_rstn(&M, T, false);
	assert_int_equal(M.stats.backpowered, 1);
	as9888_model_set_rstn(&M, T, true);
	assert_int_equal(M.stats.backpowered, 2);
	as9888_model_set_rstn(&M, T, false);
	/* the right order: RSTN low, supply off, supply on, RSTN high */
	as9888_model_set_power(&M, T, true);
	at(AS9888_T_RSTL_NS);
	as9888_model_set_rstn(&M, T, true);
	at(AS9888_T_BOOT_NS);
	as9888_model_set_rstn(&M, T, false);
	at(AS9888_T_RSTL_NS);
	as9888_model_set_power(&M, T, false);
	as9888_model_set_power(&M, T, true);
	at(AS9888_T_RSTL_NS);
	as9888_model_set_rstn(&M, T, true);
	at(AS9888_T_BOOT_NS);
	assert_int_equal(rd(AS9888_REG_WIA), AS9888_WIA_VAL);
	assert_int_equal(M.stats.backpowered, 2);
	assert_int_equal(M.stats.unpowered_transfers, 2);
}

static void test_magn_measurements_counted(void **state)
{
	boot(NULL);
	wr(AS9888_REG_MS, AS9888_MS_SINGLE);
	at(AS9888_T_ACC_NS + AS9888_T_PD_NS);
	wr(AS9888_REG_SLCT2, AS9888_SLCT2_MEN_MSK);
	wr(AS9888_REG_MS, AS9888_MS_SINGLE);
	at(AS9888_T_MAG_NS + AS9888_T_PD_NS);
	wr(AS9888_REG_SLCT2, 0);
	wr(AS9888_REG_MS, AS9888_MS_SELF_TEST);
	at(AS9888_T_MAG_NS);
	as9888_model_advance(&M, T);
	assert_int_equal(M.stats.measurements, 3);
	assert_int_equal(M.stats.magn_measurements, 2);
}

static void test_peek_no_side_effects(void **state)
{
	u64 reads;

	ready(NULL);
	wr(AS9888_REG_INT1EN, 1);
	wr(AS9888_REG_SLCT2, AS9888_SLCT2_ALPF_MSK);
	reads = M.stats.reads;
	assert_int_equal(as9888_model_peek(&M, AS9888_REG_INT1EN), 1);
	assert_int_equal(as9888_model_peek(&M, AS9888_REG_SLCT2),
			 AS9888_SLCT2_ALPF_MSK);
	assert_int_equal(as9888_model_peek(&M, AS9888_REG_REF1), rd(AS9888_REG_REF1));
	assert_int_equal(as9888_model_peek(&M, AS9888_REG_AZDA), rd(AS9888_REG_AZDA));
	assert_int_equal(as9888_model_peek(&M, AS9888_REG_ST2), 0);
	assert_int_equal(M.stats.reads, reads + 2);
}

static void test_reset_short_pulse_ignored(void **state)
{
	ready(NULL);
	wr(AS9888_REG_INT1EN, 1);
	as9888_model_set_rstn(&M, T, false);
	at(AS9888_T_RSTL_NS - 1);
	as9888_model_set_rstn(&M, T, true);
	/* no boot time either */
	assert_int_equal(rd(AS9888_REG_INT1EN), 1);
	assert_int_equal(rd(AS9888_REG_REF1), 0x9a);
	assert_int_equal(M.stats.resets, 0);
}

static void test_reset_boot_nak(void **state)
{
	u8 v;

	ready(NULL);
	as9888_model_set_rstn(&M, T, false);
	/* held in reset: no answer */
	assert_int_equal(as9888_model_read(&M, T, 0, &v, 1), -EIO);
	at(1 * MSEC);
	assert_int_equal(as9888_model_write(&M, T, 2, &v, 1), -EIO);
	as9888_model_set_rstn(&M, T, true);
	at(AS9888_T_BOOT_NS - 1);
	assert_int_equal(as9888_model_read(&M, T, 0, &v, 1), -EIO);
	assert_int_equal(as9888_model_write(&M, T, 2, &v, 1), -EIO);
	at(1);
	assert_int_equal(rd(AS9888_REG_WIA), 0x48);
	assert_int_equal(M.stats.naks, 4);
}

static void test_power_on_boot_nak(void **state)
{
	u8 v = 1;

	T = 1000;
	as9888_model_init(&M, NULL, T);
	assert_int_equal(as9888_model_read(&M, T, 0, &v, 1), -EIO);
	at(AS9888_T_BOOT_NS - 1);
	assert_int_equal(as9888_model_write(&M, T, AS9888_REG_INT1EN, &v, 1),
			 -EIO);
	at(1);
	assert_int_equal(rd(AS9888_REG_INT1EN), 0);	/* write was lost */
	assert_int_equal(rd(AS9888_REG_WIA), 0x48);
}

static void test_spi_boot_reads_ff(void **state)
{
	u8 b[3] = { 0, 0, 0 }, v = 1;

	T = 1000;
	as9888_model_init(&M, NULL, T);
	as9888_model_set_bus(&M, AS9888_BUS_SPI);
	assert_int_equal(as9888_model_read(&M, T, 0, b, 3), 0);
	assert_int_equal(b[0], 0xff);
	assert_int_equal(b[2], 0xff);
	assert_int_equal(as9888_model_write(&M, T, AS9888_REG_INT1EN, &v, 1),
			 0);
	at(AS9888_T_BOOT_NS);
	assert_int_equal(rd(AS9888_REG_INT1EN), 0);	/* dropped */
	assert_int_equal(rd(AS9888_REG_WIA), 0x48);
	assert_int_equal(M.stats.naks, 2);
}

static void test_reset_aborts_measurement(void **state)
{
	ready(NULL);
	wr(AS9888_REG_INT1EN, 1);
	wr(AS9888_REG_MS, AS9888_MS_SINGLE);
	at(100 * US);
	as9888_model_set_rstn(&M, T, false);
	at(10 * MSEC);
	as9888_model_set_rstn(&M, T, true);
	at(AS9888_T_BOOT_NS);
	assert_false(pin1());
	assert_int_equal(rd(AS9888_REG_MS), 0);
	assert_int_equal(rd(AS9888_REG_ST1), 0);
	assert_int_equal(M.stats.measurements, 0);
	assert_int_equal(M.stats.aborted, 1);
}

static void test_reset_takes_effect_after_trstl(void **state)
{
	/* a measurement ending within t_RSTL of the falling edge completes,
	 * then the reset clears it */
	ready(NULL);
	wr(AS9888_REG_INT1EN, 1);
	wr(AS9888_REG_MS, AS9888_MS_SINGLE);
	at(AS9888_T_ACC_NS - 2 * US);
	as9888_model_set_rstn(&M, T, false);
	at(4 * US);
	assert_true(pin1());
	at(AS9888_T_RSTL_NS);
	assert_false(pin1());
	assert_int_equal(M.stats.measurements, 1);
	assert_int_equal(M.stats.resets, 1);
}

/* ---- timing ---- */

static void duration_case(u8 slct2, u8 mode, u64 expect)
{
	ready(NULL);
	wr(AS9888_REG_INT1EN, 1);
	wr(AS9888_REG_SLCT2, slct2);
	wr(AS9888_REG_MS, mode);
	assert_int_equal(as9888_model_next_event_ns(&M), T + expect);
	at(expect - 1);
	assert_false(pin1());
	assert_int_equal(rd(AS9888_REG_ST1), 0);
	at(1);
	assert_true(pin1());
	assert_int_equal(rd(AS9888_REG_ST1), AS9888_ST1_DRDY_MSK);
	assert_int_equal(as9888_model_next_event_ns(&M), U64_MAX);
}

static void test_duration_acc(void **state)
{
	duration_case(0, AS9888_MS_SINGLE, 1200 * US);
}

static void test_duration_acc_lpf(void **state)
{
	duration_case(AS9888_SLCT2_ALPF_MSK, AS9888_MS_SINGLE, 4800 * US);
}

static void test_duration_mag(void **state)
{
	duration_case(AS9888_SLCT2_MEN_MSK, AS9888_MS_SINGLE, 7300 * US);
	duration_case(AS9888_SLCT2_MEN_MSK | AS9888_SLCT2_ALPF_MSK, AS9888_MS_SINGLE,
		      7300 * US);
}

static void test_duration_self_test(void **state)
{
	duration_case(0, AS9888_MS_SELF_TEST, 7300 * US);
	duration_case(AS9888_SLCT2_ALPF_MSK, AS9888_MS_SELF_TEST, 7300 * US);
}

static void test_slct2_sampled_at_start(void **state)
{
	ready(NULL);
	wr(AS9888_REG_MS, AS9888_MS_SINGLE);
	wr(AS9888_REG_SLCT2, AS9888_SLCT2_MEN_MSK);
	at(AS9888_T_ACC_NS);
	assert_int_equal(rd(AS9888_REG_ST1), AS9888_ST1_DRDY_MSK);
	assert_int_equal(rd(AS9888_REG_ST2), AS9888_ST2_HST_MSK);
}

static void test_time_never_decreases(void **state)
{
	u8 v;

	ready(NULL);
	wr(AS9888_REG_INT1EN, 1);
	wr(AS9888_REG_MS, AS9888_MS_SINGLE);
	at(AS9888_T_ACC_NS);
	assert_true(pin1());
	/* an earlier time is treated as the latest one seen */
	assert_true(as9888_model_pin(&M, T - AS9888_T_ACC_NS,
				     AS9888_PIN_INT1));
	assert_int_equal(as9888_model_read(&M, 0, AS9888_REG_ST1, &v, 1), 0);
	assert_int_equal(v, AS9888_ST1_DRDY_MSK);
	/* and t_PD is not broken by going back */
	wr(AS9888_REG_MS, AS9888_MS_EEPROM);
	assert_int_equal(rd(AS9888_REG_MS), 0);
}

/* ---- temperature ---- */

static void tmps_case(s32 mdegc, u8 expect)
{
	struct as9888_unit u = unit_default();
	struct sample s;

	u.temperature_mdegc = mdegc;
	ready(&u);
	measure(0, &s);
	assert_int_equal(s.tmps, expect);
	/* the datasheet formula in double */
	assert_int_equal(expect, (u8)fmin(fmax(rint(176 - 1.6 * mdegc / 1000.0),
					       0), 255));
}

static void test_tmps_values(void **state)
{
	tmps_case(25000, 136);
	tmps_case(31250, 126);
	tmps_case(-30000, 224);
	tmps_case(85000, 40);
	tmps_case(0, 176);
	tmps_case(20312, 144);		/* 143.5008 */
	tmps_case(20313, 143);		/* 143.4992 */
	tmps_case(19687, 145);		/* 144.5008 */
	tmps_case(19688, 144);		/* 144.4992 */
	tmps_case(-50000, 255);		/* clamped */
	tmps_case(150000, 0);		/* clamped */
}

static void test_tmps_drift(void **state)
{
	struct as9888_unit u = unit_default();
	struct sample s;

	u.temperature_mdegc = 25000;
	u.drift_udegc_s = 500000;	/* 0.5 degC/s */
	ready(&u);
	measure(0, &s);
	assert_int_equal(s.tmps, 136);
	T = M.init_ns + 10000 * MSEC;	/* 30 degC at the next end */
	wr(AS9888_REG_MS, AS9888_MS_SINGLE);
	at(AS9888_T_ACC_NS);
	read_sample(&s);
	assert_int_equal(s.tmps, 128);	/* 176 - 48 = 128 (30.0006 degC) */
	T = M.init_ns + 100000 * MSEC;	/* 75 degC */
	measure(0, &s);
	assert_int_equal(s.tmps, 56);
	T = M.init_ns + 1000000 * MSEC;	/* 525 degC: clamped at 150 */
	measure(0, &s);
	assert_int_equal(s.tmps, 0);
}

static void test_tmps_every_measurement(void **state)
{
	struct as9888_unit u = unit_default();
	struct sample s;

	u.drift_udegc_s = -1000000;	/* -1 degC/s */
	ready(&u);
	measure(0, &s);
	assert_int_equal(s.tmps, 136);
	T += 5000 * MSEC;
	measure_mode(0, AS9888_MS_SELF_TEST, &s);
	assert_int_equal(s.tmps, 144);
	T += 5000 * MSEC;
	measure(AS9888_SLCT2_MEN_MSK, &s);
	assert_int_equal(s.tmps, 152);
	T += 5000 * MSEC;
	measure(AS9888_SLCT2_ALPF_MSK, &s);
	assert_int_equal(s.tmps, 160);
}

/* ---- accelerometer ---- */

static void check_accel(const struct as9888_unit *u, u8 slct2)
{
	struct sample s;
	u8 trim[10];
	double t;
	int i;

	measure(slct2, &s);
	rdn(AS9888_REG_REF1, trim, 10);
	t = (176 - s.tmps) / 1.6;	/* only a sanity check */
	(void)t;
	for (i = 0; i < 3; i++) {
		double v = ref_accel(u, i, trim[4 + i], trim[7 + i],
				     u->temperature_mdegc / 1000.0);
		s64 n = as9888_model_accel_nlsb(&M, i, u->temperature_mdegc);

		/* micro-LSB agreement of the fixed point with the double */
		assert_true(fabs(n / 1e9 - v) < 1e-6);
		expect_raw(v, s.a[i], -2048, 2047);
	}
}

static void test_accel_default_unit(void **state)
{
	struct as9888_unit u = unit_default();

	u.noise_mlsb = 0;
	ready(&u);
	check_accel(&u, 0);
	check_accel(&u, AS9888_SLCT2_ALPF_MSK);
	check_accel(&u, AS9888_SLCT2_MEN_MSK);
}

static void set_up(struct as9888_unit *u, s32 x, s32 y, s32 z)
{
	s32 in[3] = { x, y, z };

	assert_int_equal(as9888_unit_normalise(in, u->up), 0);
}

static void test_accel_units(void **state)
{
	static const u8 ee2[21] = {
		0x9a, 0x71, 0xf5, 0x5c, 0x80, 0x85, 0x7b, 0x47, 0xab, 0x8a,
		0xff, 0x00, 0x80, 0xc3, 0x00, 0x43, 0xff, 0x10, 0xe0, 0x90,
		0x40,
	};
	struct as9888_unit u = unit_default();
	int i;

	u.noise_mlsb = 0;
	/* tilted, offsets, warm */
	set_up(&u, 300, -200, 930);
	u.offset_mlsb[0] = 40000;
	u.offset_mlsb[1] = -25000;
	u.offset_mlsb[2] = 60500;
	u.temperature_mdegc = 31250;
	ready(&u);
	check_accel(&u, 0);

	/* upside down, cold, other EEPROM (polarity bits, negative DT) */
	memcpy(u.eeprom, ee2, 21);
	set_up(&u, 0, 0, -1);
	u.temperature_mdegc = -20000;
	ready(&u);
	check_accel(&u, 0);

	/* X up, hot */
	set_up(&u, 1, 0, 0);
	u.temperature_mdegc = 84000;
	u.offset_mlsb[0] = -123456;
	ready(&u);
	check_accel(&u, 0);

	/* random tilts and temperatures with the default EEPROM */
	as9888_unit_default(&u);
	u.noise_mlsb = 0;
	for (i = 0; i < 40; i++) {
		set_up(&u, (i * 37) % 200 - 100, (i * 53) % 200 - 100,
		       (i * 71) % 200 - 100 + (i == 0));
		u.temperature_mdegc = -40000 + i * 3137;
		u.offset_mlsb[i % 3] = (i * 7919) % 300000 - 150000;
		ready(&u);
		check_accel(&u, 0);
	}
}

static void test_accel_kote_fallback(void **state)
{
	struct as9888_unit u = unit_default();
	struct sample s1, s2;

	u.noise_mlsb = 0;
	u.temperature_mdegc = 65000;
	/* ET2 outside 0x28..0xe0: dT = 35 degC */
	u.eeprom[20] = 0x20;
	ready(&u);
	check_accel(&u, 0);
	measure(0, &s1);
	/* ET span of 70 codes = 43.75 degC: a different Kote */
	u.eeprom[19] = 0x90;
	u.eeprom[20] = 0x4a;
	ready(&u);
	check_accel(&u, 0);
	measure(0, &s2);
	assert_int_not_equal(s1.a[0], s2.a[0]);
	/* span of 8 codes = 5 degC < 10: fallback */
	u.eeprom[19] = 0x88;
	u.eeprom[20] = 0x80;
	ready(&u);
	check_accel(&u, 0);
	/* span of 130 codes = 81.25 degC > 80: fallback */
	u.eeprom[19] = 0xd0;
	u.eeprom[20] = 0x4e;
	ready(&u);
	check_accel(&u, 0);
	measure(0, &s2);
	assert_int_equal(s1.a[0], s2.a[0]);
}

static void test_accel_dac_effect(void **state)
{
	struct as9888_unit u = unit_default();
	struct sample s0, s1;
	int axis;

	u.noise_mlsb = 0;
	ready(&u);
	measure(0, &s0);
	for (axis = 0; axis < 3; axis++) {
		u8 ga = rd(AS9888_REG_AXGA + axis);
		u8 da = rd(AS9888_REG_AXDA + axis);
		int lin = ref_dac2lin(ga, da);
		int nlin = lin + 5;
		u8 nda;
		double step = 2048.0 / ((ga & 63) + 16);

		nlin = (ga & 0x40) ? -nlin : nlin;
		nda = nlin >= 0 ? nlin + 0x80 : -nlin;
		wr(AS9888_REG_AXDA + axis, nda);
		measure(0, &s1);
		/* +5 linear codes move the output up by 5 steps */
		assert_true(fabs(s1.a[axis] - s0.a[axis] - 5 * step) <= 1.0);
		check_accel(&u, 0);
		wr(AS9888_REG_AXDA + axis, da);
	}
}

static void test_accel_gain_register(void **state)
{
	struct as9888_unit u = unit_default();
	struct sample s0, s1;

	u.noise_mlsb = 0;
	ready(&u);
	measure(0, &s0);
	/* Z gain 34 -> 43: sensitivity * 59/50 and the DAC step changes */
	wr(AS9888_REG_AZGA, (rd(AS9888_REG_AZGA) & 0x40) | 43);
	check_accel(&u, 0);
	measure(0, &s1);
	assert_true(s1.a[2] > s0.a[2] + 40);
	/* X polarity flipped against EAXGA: the DAC code -13 becomes +13,
	 * 26 codes of 2048 / 44 LSB */
	wr(AS9888_REG_AXGA, rd(AS9888_REG_AXGA) ^ 0x40);
	check_accel(&u, 0);
	measure(0, &s1);
	assert_true(fabs(s1.a[0] - s0.a[0] - 26 * 2048.0 / 44) <= 1.0);
}

static void test_accel_untrimmed(void **state)
{
	struct sample s;

	boot(NULL);
	measure(0, &s);
	assert_int_equal(s.a[0], 2047);
	assert_int_equal(s.a[1], 2047);
	assert_int_equal(s.a[2], 2047);
	/* one gain missing: only that axis saturates */
	at(AS9888_T_PD_NS);
	load_trim();
	wr(AS9888_REG_AYGA, 0);
	measure(0, &s);
	assert_true(s.a[0] < 100 && s.a[0] > -100);
	assert_int_equal(s.a[1], 2047);
	assert_true(s.a[2] > 150 && s.a[2] < 350);
}

static void test_accel_ref3_wrong(void **state)
{
	struct sample s;

	ready(NULL);
	wr(AS9888_REG_REF3, 0x15);	/* EREF3 itself instead of 0x1d */
	measure(0, &s);
	assert_int_equal(s.a[0], 2047);
	assert_int_equal(s.a[1], 2047);
	assert_int_equal(s.a[2], 2047);
	wr(AS9888_REG_REF3, 0x1d);
	measure(0, &s);
	assert_true(s.a[2] > 150 && s.a[2] < 350);
}

static void test_accel_clamped(void **state)
{
	struct as9888_unit u = unit_default();
	struct sample s;

	u.noise_mlsb = 0;
	u.offset_mlsb[0] = 3000000;
	u.offset_mlsb[1] = -3000000;
	ready(&u);
	measure(0, &s);
	assert_int_equal(s.a[0], 2047);
	assert_int_equal(s.a[1], -2048);
}

/* rint(): ties to even (D5), in the accelerometer and magnetometer */
static void test_rounding_ties_to_even(void **state)
{
	static const struct {
		s32 off_mlsb;
		s16 expect;
	} c[] = {
		{ 500, 0 }, { 1500, 2 }, { 2500, 2 }, { -500, 0 },
		{ -1500, -2 }, { -2500, -2 }, { 2501, 3 }, { 2499, 2 },
	};
	struct as9888_unit u = unit_default();
	struct sample s;
	unsigned int i;

	u.noise_mlsb = 0;
	u.up[0] = 1000000;	/* X up: Y and Z see no gravity */
	u.up[2] = 0;
	u.eeprom[4] = 0x80;	/* EHCX = 128: 300 nT per LSB exactly */
	for (i = 0; i < sizeof(c) / sizeof(c[0]); i++) {
		u.offset_mlsb[1] = c[i].off_mlsb;
		u.field_nt[0] = c[i].off_mlsb * 3 / 10;	/* same in LSB */
		ready(&u);
		measure(AS9888_SLCT2_MEN_MSK, &s);
		assert_int_equal(s.a[1], c[i].expect);
		if (c[i].off_mlsb % 10 == 0)	/* field exact in nT */
			assert_int_equal(s.h[0], c[i].expect);
	}
}

/* ---- magnetometer ---- */

static void test_mag_values(void **state)
{
	struct as9888_unit u = unit_default();
	struct sample s;
	int i, k;

	for (k = 0; k < 6; k++) {
		u.field_nt[0] = 20000 - k * 71111;
		u.field_nt[1] = -5000 + k * 123457;
		u.field_nt[2] = -40000 + k * 13;
		u.eeprom[4] = 0x80 + k * 20;
		u.eeprom[5] = 0x85 - k * 21;
		ready(&u);
		measure(AS9888_SLCT2_MEN_MSK, &s);
		for (i = 0; i < 3; i++)
			expect_raw(ref_mag(&u, i, 0), s.h[i], -4096, 4095);
	}
}

static void test_mag_self_test(void **state)
{
	static const double gen[3] = { -20, 15, 600 };
	struct as9888_unit u = unit_default();
	struct sample s;
	int i;

	ready(&u);
	measure_mode(0, AS9888_MS_SELF_TEST, &s);
	assert_int_equal(s.st2, 0);
	for (i = 0; i < 3; i++) {
		double adj;

		expect_raw(ref_mag(&u, i, gen[i]), s.h[i], -4096, 4095);
		/* after adjustment: ambient + generator, about +-1 LSB */
		adj = s.h[i] * (u.eeprom[4 + i] + 128) / 256.0;
		assert_true(fabs(adj - (u.field_nt[i] / 300.0 + gen[i])) < 1.1);
	}
	/* zero ambient field: reads about (-20, 15, 600) */
	u.field_nt[0] = u.field_nt[1] = u.field_nt[2] = 0;
	ready(&u);
	measure_mode(0, AS9888_MS_SELF_TEST, &s);
	for (i = 0; i < 3; i++)
		assert_true(fabs(s.h[i] * (u.eeprom[4 + i] + 128) / 256.0 -
				 gen[i]) < 1.1);
}

static void test_mag_self_test_keeps_accel(void **state)
{
	struct as9888_unit u = unit_default();
	struct sample s1, s2;

	u.noise_mlsb = 5000;
	ready(&u);
	measure(0, &s1);
	measure_mode(0, AS9888_MS_SELF_TEST, &s2);
	assert_memory_equal(s1.a, s2.a, sizeof(s1.a));
}

/* ---- noise ---- */

static void noise_stats(u8 slct2, double expect_rms)
{
	struct as9888_unit u = unit_default();
	double sum = 0, sum2 = 0, ref[3];
	struct sample s;
	u8 trim[10];
	int n = 0, i, k;

	u.noise_mlsb = 10000;		/* 10 LSB */
	u.seed = 12345;
	ready(&u);
	rdn(AS9888_REG_REF1, trim, 10);
	for (i = 0; i < 3; i++)
		ref[i] = ref_accel(&u, i, trim[4 + i], trim[7 + i], 25.0);
	for (k = 0; k < 1500; k++) {
		measure(slct2, &s);
		for (i = 0; i < 3; i++) {
			double d = s.a[i] - ref[i];

			sum += d;
			sum2 += d * d;
			n++;
		}
	}
	sum /= n;
	sum2 = sqrt(sum2 / n - sum * sum);
	/* rms includes the rounding (1/12 LSB^2); 3.5 sigma bounds */
	expect_rms = sqrt(expect_rms * expect_rms + 1.0 / 12);
	assert_true(fabs(sum) < 3.5 * expect_rms / sqrt(n));
	assert_true(fabs(sum2 - expect_rms) < 3.5 * expect_rms / sqrt(2.0 * n));
}

static void test_noise_rms(void **state)
{
	noise_stats(0, 10.0);
}

static void test_noise_rms_alpf(void **state)
{
	noise_stats(AS9888_SLCT2_ALPF_MSK, 5.0);
}

static void test_noise_zero(void **state)
{
	struct as9888_unit u = unit_default();
	struct sample s0, s;
	int k;

	u.noise_mlsb = 0;
	ready(&u);
	measure(0, &s0);
	for (k = 0; k < 50; k++) {
		measure(0, &s);
		assert_memory_equal(s.a, s0.a, sizeof(s.a));
	}
}

/* ---- live environment (the test adapter's debugfs knobs) ---- */

/* Every axis of @s against the reference for unit @u at @t degC */
static void expect_accel(const struct as9888_unit *u, const struct sample *s,
			 double t)
{
	u8 trim[10];
	int i;

	rdn(AS9888_REG_REF1, trim, 10);
	for (i = 0; i < 3; i++)
		expect_raw(ref_accel(u, i, trim[4 + i], trim[7 + i], t),
			   s->a[i], -2048, 2047);
}

static void test_live_temperature(void **state)
{
	struct as9888_unit u = unit_default();
	struct as9888_model_stats st0;
	struct sample s;
	u8 trim[10], trim1[10];

	u.noise_mlsb = 0;
	ready(&u);
	measure(0, &s);
	assert_int_equal(s.tmps, 136);
	rdn(AS9888_REG_REF1, trim, 10);
	st0 = *as9888_model_stats(&M);

	as9888_model_set_temperature(&M, T, 70000);
	measure(0, &s);
	assert_int_equal(s.tmps, 64);
	u.temperature_mdegc = 70000;
	expect_accel(&u, &s, 70);
	/* the chip was not reset: trim kept, counters carry on */
	rdn(AS9888_REG_REF1, trim1, 10);
	assert_memory_equal(trim, trim1, 10);
	assert_int_equal(as9888_model_stats(&M)->resets, st0.resets);
	assert_int_equal(as9888_model_stats(&M)->measurements,
			 st0.measurements + 1);

	/* a measurement running across the change completes with the new value */
	at(AS9888_T_PD_NS);
	wr(AS9888_REG_SLCT2, 0);
	wr(AS9888_REG_MS, AS9888_MS_SINGLE);
	at(AS9888_T_ACC_NS / 2);
	as9888_model_set_temperature(&M, T, -20000);
	at(AS9888_T_ACC_NS);
	read_sample(&s);
	assert_int_equal(s.tmps, 208);
	u.temperature_mdegc = -20000;
	expect_accel(&u, &s, -20);

	/* one that completed before the change keeps the old value */
	at(AS9888_T_PD_NS);
	wr(AS9888_REG_MS, AS9888_MS_SINGLE);
	at(AS9888_T_ACC_NS);
	as9888_model_set_temperature(&M, T, 25000);
	read_sample(&s);
	assert_int_equal(s.tmps, 208);

	/* the drift continues from the new value; clamped like a unit */
	u.drift_udegc_s = 1000000;	/* 1 degC/s */
	ready(&u);
	T += 10000 * MSEC;
	as9888_model_set_temperature(&M, T, 0);
	assert_int_equal(as9888_model_temperature_mdegc(&M, T), 0);
	assert_int_equal(as9888_model_temperature_mdegc(&M, T + 5000 * MSEC),
			 5000);
	as9888_model_set_temperature(&M, T, INT32_MIN);
	assert_int_equal(as9888_model_temperature_mdegc(&M, T),
			 AS9888_UNIT_TEMP_MIN_MDEGC);
}

static void test_live_up(void **state)
{
	static const s32 postures[][3] = {
		{ 0, 0, -1 }, { -1, 0, 0 }, { 0, 1, 0 }, { 300, -200, 930 },
	};
	struct as9888_unit u = unit_default();
	struct sample s;
	unsigned int k;
	u64 resets;

	u.noise_mlsb = 0;
	u.offset_mlsb[0] = 40000;
	ready(&u);
	resets = as9888_model_stats(&M)->resets;
	measure(0, &s);
	expect_accel(&u, &s, 25);
	assert_true(s.a[2] > 200);
	for (k = 0; k < ARRAY_SIZE(postures); k++) {
		set_up(&u, postures[k][0], postures[k][1], postures[k][2]);
		as9888_model_set_up(&M, T, u.up);
		measure(0, &s);
		expect_accel(&u, &s, 25);
	}
	assert_int_equal(as9888_model_stats(&M)->resets, resets);
}

static void test_live_noise(void **state)
{
	struct as9888_unit u = unit_default();
	struct sample s0, s;
	int k, differ = 0;

	u.noise_mlsb = 0;
	ready(&u);
	measure(0, &s0);
	as9888_model_set_noise(&M, T, 5000);
	for (k = 0; k < 20; k++) {
		measure(0, &s);
		differ += memcmp(s.a, s0.a, sizeof(s.a)) != 0;
	}
	assert_true(differ > 10);
	as9888_model_set_noise(&M, T, 0);
	for (k = 0; k < 20; k++) {
		measure(0, &s);
		assert_memory_equal(s.a, s0.a, sizeof(s.a));
	}
}

static void run_seq(u64 seed, s16 out[60][3])
{
	struct as9888_unit u = unit_default();
	struct sample s;
	int k;

	u.seed = seed;
	u.noise_mlsb = 3000;
	ready(&u);
	for (k = 0; k < 60; k++) {
		measure(k & 1 ? AS9888_SLCT2_ALPF_MSK : 0, &s);
		memcpy(out[k], s.a, sizeof(s.a));
	}
}

static void test_noise_seed_determinism(void **state)
{
	static s16 a[60][3], b[60][3], c[60][3];

	run_seq(42, a);
	run_seq(42, b);
	run_seq(43, c);
	assert_memory_equal(a, b, sizeof(a));
	assert_memory_not_equal(a, c, sizeof(a));
}

/* ---- the magnetic world ---- */

#define MEN	AS9888_SLCT2_MEN_MSK

/* A magnetometer reading in uT after the sensitivity adjustment */
static double mag_ut(const struct as9888_unit *u, const struct sample *s,
		     int axis)
{
	return s->h[axis] * (u->eeprom[4 + axis] + 128) / 256.0 * 0.3;
}

/* Within half a count (about 0.15 uT) plus @tol of (x, y, z) uT */
static void expect_mag(const struct as9888_unit *u, const struct sample *s,
		       double x, double y, double z, double tol)
{
	double want[3] = { x, y, z };
	int i;

	for (i = 0; i < 3; i++)
		if (fabs(mag_ut(u, s, i) - want[i]) > 0.16 + tol)
			fail_msg("axis %d: %.3f uT, want %.3f", i,
				 mag_ut(u, s, i), want[i]);
}

static struct as9888_unit unit_world(void)
{
	struct as9888_unit u = unit_default();

	u.noise_mlsb = 0;
	u.world = AS9888_UNIT_WORLD_EARTH;
	u.earth_nt = 50000;
	u.incl_mdeg = 60000;
	return u;
}

/* Level: the field turns with the heading; the accelerometer does not */
static void test_world_earth_heading(void **state)
{
	struct as9888_unit u = unit_world();
	struct sample s0, s;
	s64 f[3];

	ready(&u);
	measure(MEN, &s0);
	expect_mag(&u, &s0, 0, 25, -43.301, 0);
	as9888_model_set_heading(&M, T, 90000);
	measure(MEN, &s);
	/* +Y points east: north is -X */
	expect_mag(&u, &s, -25, 0, -43.301, 0);
	as9888_model_field_nt(&M, f);
	assert_true(llabs(f[0] + 25000) <= 1 && llabs(f[1]) <= 1);
	assert_memory_equal(s.a, s0.a, sizeof(s.a));
	/* declination: magnetic north 10 deg east of true north */
	as9888_model_set_earth(&M, T, 50000, 60000, 10000);
	as9888_model_set_heading(&M, T, 10000);
	measure(MEN, &s);
	expect_mag(&u, &s, 0, 25, -43.301, 0.001);
}

/* The sensor's +Y up: the accelerometer reads as with "up = 0 1 0" */
static void test_world_orientation_moves_accel(void **state)
{
	static const s32 q[4] = { 1000000, 1000000, 0, 0 };
	struct as9888_unit u = unit_world(), v = unit_world();
	struct sample s, r;

	v.up[1] = 1000000;
	v.up[2] = 0;
	ready(&v);
	measure(0, &r);
	ready(&u);
	as9888_model_set_orientation(&M, T, q);
	assert_int_equal(M.unit.up[1], 1000000);
	measure(MEN, &s);
	assert_memory_equal(s.a, r.a, sizeof(s.a));
	/* world up (the field's -43.3 uT) is now along +Y, north along -Z */
	expect_mag(&u, &s, 0, -43.301, -25, 0);
	/* "up" again gives the tilt back and keeps the heading */
	as9888_model_set_up(&M, T, (s32[3]){ 0, 0, 1000000 });
	measure(MEN, &s);
	expect_mag(&u, &s, 0, 25, -43.301, 0);
}

/* Reads S (B + d) + h: iron applies to the fixed "field" as well */
static void test_world_iron(void **state)
{
	static const s32 soft[9] = { 1050000, 20000, 0, 20000, 950000, -30000,
				     0, -30000, 1000000 };
	static const s32 hard[3] = { 100000, -50000, 20000 };
	struct as9888_unit u = unit_default();
	struct sample s;

	u.noise_mlsb = 0;
	ready(&u);
	as9888_model_set_hard_iron(&M, T, hard);
	as9888_model_set_soft_iron(&M, T, soft);
	measure(MEN, &s);
	/* field (20, -5, -40) */
	expect_mag(&u, &s, 1.05 * 20 - 0.02 * 5 + 100,
		   0.02 * 20 - 0.95 * 5 + 0.03 * 40 - 50,
		   0.03 * 5 - 40 + 20, 0);
}

/* A passing magnet: a half sine over n measurements, then nothing */
static void test_world_disturbance(void **state)
{
	static const s32 d[3] = { 300000, 0, -100000 };
	static const double k[5] = { 0.70711, 1, 0.70711, 0, 0 };
	struct as9888_unit u = unit_default();
	struct sample s;
	int i;

	u.noise_mlsb = 0;
	ready(&u);
	measure(0, &s);		/* accelerometer only: does not count */
	as9888_model_set_disturbance(&M, T, d, 3);
	measure(0, &s);
	for (i = 0; i < 5; i++) {
		measure(MEN, &s);
		expect_mag(&u, &s, 20 + 300 * k[i], -5, -40 - 100 * k[i],
			   0.001);
	}
	/* n = 0: constant */
	as9888_model_set_disturbance(&M, T, d, 0);
	for (i = 0; i < 3; i++) {
		measure(MEN, &s);
		expect_mag(&u, &s, 320, -5, -140, 0);
	}
}

/* Noise of the stated rms; the accelerometer's samples stay the same */
static void test_world_noise(void **state)
{
	struct as9888_unit u = unit_default();
	static s16 acc[400][3];
	double sum[3] = { 0 }, sq[3] = { 0 }, rms;
	struct sample s;
	int i, j, n = 400;

	ready(&u);
	for (i = 0; i < n; i++) {
		measure(MEN, &s);
		memcpy(acc[i], s.a, sizeof(s.a));
	}
	u.magn_noise_nt = 600;
	ready(&u);
	for (i = 0; i < n; i++) {
		measure(MEN, &s);
		assert_memory_equal(acc[i], s.a, sizeof(s.a));
		for (j = 0; j < 3; j++) {
			sum[j] += mag_ut(&u, &s, j);
			sq[j] += mag_ut(&u, &s, j) * mag_ut(&u, &s, j);
		}
	}
	for (j = 0; j < 3; j++) {
		rms = sqrt(sq[j] / n - (sum[j] / n) * (sum[j] / n));
		/* 0.6 uT and the quantisation (0.087 uT): 0.606 */
		if (rms < 0.54 || rms > 0.68)
			fail_msg("axis %d: rms %.3f uT", j, rms);
		assert_true(fabs(sum[j] / n - u.field_nt[j] / 1000.0) < 0.1);
	}
}

static double quat_angle_deg(const s32 a[4], const s32 b[4])
{
	double dot = 0;
	int i;

	for (i = 0; i < 4; i++)
		dot += (double)a[i] / (1 << 30) * b[i] / (1 << 30);
	return 2 * acos(fmin(1, fabs(dot))) * 180 / M_PI;
}

/*
 * Tumble: each measurement turns the device by the set angle; up and the
 * field follow the orientation; seeded; in time it sees every octant.
 */
static void test_world_tumble(void **state)
{
	struct as9888_unit u = unit_world();
	s32 q0[4], q1[4], first[4];
	unsigned int octants = 0;
	struct sample s;
	s64 f[3];
	int i;

	u.tumble_mdeg = 7000;
	u.seed = 99;
	ready(&u);
	as9888_model_orientation(&M, q0);
	measure(0, &s);
	as9888_model_orientation(&M, first);
	for (i = 0; i < 600; i++) {
		double fu;

		as9888_model_orientation(&M, q0);
		measure(i & 1 ? MEN : 0, &s);
		as9888_model_orientation(&M, q1);
		assert_true(fabs(quat_angle_deg(q0, q1) - 7) < 0.01);
		/* the field's component along up is always -F sin I */
		as9888_model_field_nt(&M, f);
		fu = ((double)f[0] * M.unit.up[0] + (double)f[1] * M.unit.up[1] +
		      (double)f[2] * M.unit.up[2]) / 1e6;
		assert_true(fabs(fu + 43301) < 3);
		octants |= 1u << ((M.unit.up[0] > 0) | (M.unit.up[1] > 0) << 1 |
				  (M.unit.up[2] > 0) << 2);
		if (i & 1)
			expect_mag(&u, &s, f[0] / 1000.0, f[1] / 1000.0,
				   f[2] / 1000.0, 0.001);
	}
	assert_int_equal(octants, 0xff);
	/* the same seed, the same motion */
	ready(&u);
	measure(0, &s);
	as9888_model_orientation(&M, q1);
	assert_memory_equal(q1, first, sizeof(q1));
	/* stopped: it stays */
	as9888_model_set_tumble(&M, T, 0);
	measure(0, &s);
	as9888_model_orientation(&M, q0);
	assert_memory_equal(q0, q1, sizeof(q0));
}

/* ---- faults ---- */

static struct as9888_unit unit_fault(u32 fault)
{
	struct as9888_unit u = unit_default();

	u.faults = fault;
	return u;
}

static void test_fault_no_drdy(void **state)
{
	struct as9888_unit u = unit_fault(AS9888_FAULT_NO_DRDY);

	ready(&u);
	wr(AS9888_REG_INT1EN, 1);
	wr(AS9888_REG_MS, AS9888_MS_SINGLE);
	assert_int_equal(as9888_model_next_event_ns(&M), U64_MAX);
	at(1000 * MSEC);
	assert_int_equal(rd(AS9888_REG_ST1), 0);
	assert_int_equal(rd(AS9888_REG_MS), AS9888_MS_SINGLE);
	assert_false(pin1());
	wr(AS9888_REG_MS, 0);
	assert_int_equal(rd(AS9888_REG_MS), 0);
}

static void test_fault_int1_open(void **state)
{
	struct as9888_unit u = unit_fault(AS9888_FAULT_INT1_OPEN);

	ready(&u);
	wr(AS9888_REG_INT1EN, 1);
	wr(AS9888_REG_INT2EN, 1);
	wr(AS9888_REG_MS, AS9888_MS_SINGLE);
	at(AS9888_T_ACC_NS);
	assert_false(pin1());
	assert_true(pin2());
	assert_int_equal(rd(AS9888_REG_INT1ST), 1);
	assert_int_equal(rd(AS9888_REG_ST1), AS9888_ST1_DRDY_MSK);
	assert_int_equal(as9888_model_pin_rises(&M, AS9888_PIN_INT1), 0);
	assert_int_equal(as9888_model_pin_rises(&M, AS9888_PIN_INT2), 1);
}

/*
 * A pulse between two looks: the MS write deasserts INT1 and the
 * measurement raises it again, and whoever looks only before and after
 * sees it high both times. The rise count still says it rose.
 */
static void test_pin_rises_between_looks(void **state)
{
	u32 r0;

	ready(NULL);
	wr(AS9888_REG_INT1EN, 1);
	assert_int_equal(as9888_model_pin_rises(&M, AS9888_PIN_INT1), 0);
	wr(AS9888_REG_MS, AS9888_MS_SINGLE);
	assert_false(pin1());
	at(AS9888_T_ACC_NS);
	assert_true(pin1());
	r0 = as9888_model_pin_rises(&M, AS9888_PIN_INT1);
	assert_int_equal(r0, 1);
	/* the next sample: started and done with no look in between */
	at(AS9888_T_PD_NS);
	wr(AS9888_REG_MS, AS9888_MS_SINGLE);
	at(AS9888_T_ACC_NS);
	assert_true(pin1());
	assert_int_equal(as9888_model_pin_rises(&M, AS9888_PIN_INT1), r0 + 1);
	/* INT2 only, INT1 off: INT1 stays low and does not count */
	at(AS9888_T_PD_NS);
	wr(AS9888_REG_INT2EN, 1);
	assert_int_equal(as9888_model_pin_rises(&M, AS9888_PIN_INT2), 0);
	wr(AS9888_REG_INT1EN, 0);
	wr(AS9888_REG_MS, AS9888_MS_SINGLE);
	at(AS9888_T_ACC_NS);
	assert_true(pin2());
	assert_false(pin1());
	assert_int_equal(as9888_model_pin_rises(&M, AS9888_PIN_INT1), r0 + 1);
	assert_int_equal(as9888_model_pin_rises(&M, AS9888_PIN_INT2), 1);
}

static void test_fault_int2_open(void **state)
{
	struct as9888_unit u = unit_fault(AS9888_FAULT_INT2_OPEN);

	ready(&u);
	wr(AS9888_REG_INT1EN, 1);
	wr(AS9888_REG_INT2EN, 1);
	wr(AS9888_REG_MS, AS9888_MS_SINGLE);
	at(AS9888_T_ACC_NS);
	assert_true(pin1());
	assert_false(pin2());
	assert_int_equal(rd(AS9888_REG_INT2ST), 1);
}

static void test_fault_rstn_open(void **state)
{
	struct as9888_unit u = unit_fault(AS9888_FAULT_RSTN_OPEN);

	ready(&u);
	wr(AS9888_REG_INT1EN, 1);
	as9888_model_set_rstn(&M, T, false);
	at(1 * MSEC);
	assert_int_equal(rd(AS9888_REG_WIA), 0x48);	/* still answers */
	as9888_model_set_rstn(&M, T, true);
	assert_int_equal(rd(AS9888_REG_INT1EN), 1);
	assert_int_equal(M.stats.resets, 0);
}

static void test_fault_wia(void **state)
{
	struct as9888_unit u = unit_fault(AS9888_FAULT_WIA);

	boot(&u);
	assert_int_equal(rd(AS9888_REG_WIA), 0x47);
}

static void test_fault_eeprom_blank(void **state)
{
	struct as9888_unit u = unit_fault(AS9888_FAULT_EEPROM_BLANK);
	u8 b[21];
	int i;

	u.noise_mlsb = 0;
	boot(&u);
	wr(AS9888_REG_MS, AS9888_MS_EEPROM);
	at(AS9888_T_EEP_NS - 1);
	assert_int_equal(rd(0x40), 0);
	at(1);
	rdn(AS9888_REG_EEPROM, b, 21);
	for (i = 0; i < 21; i++)
		assert_int_equal(b[i], 0xff);
	/* the physics still follows the true trim */
	wr(AS9888_REG_MS, 0);
	at(AS9888_T_PD_NS);
	load_trim_from(u.eeprom);
	check_accel(&u, 0);
}

static void test_fault_stuck_x(void **state)
{
	struct as9888_unit u = unit_fault(AS9888_FAULT_STUCK_X);
	struct sample s;
	int k, ymin = 9999, ymax = -9999;

	u.noise_mlsb = 5000;
	ready(&u);
	for (k = 0; k < 20; k++) {
		wr(AS9888_REG_AXDA, 0x80 + k);	/* DAC moves nothing */
		measure(k & 1 ? AS9888_SLCT2_ALPF_MSK : 0, &s);
		assert_int_equal(s.a[0], AS9888_MODEL_STUCK_X_VALUE);
		ymin = s.a[1] < ymin ? s.a[1] : ymin;
		ymax = s.a[1] > ymax ? s.a[1] : ymax;
	}
	assert_true(ymax > ymin);
	/* without the fault X moves with noise */
	u.faults = 0;
	ready(&u);
	measure(0, &s);
	assert_int_not_equal(s.a[0], AS9888_MODEL_STUCK_X_VALUE);
}

static void test_fault_saturate_z(void **state)
{
	struct as9888_unit u = unit_fault(AS9888_FAULT_SATURATE_Z);
	struct sample s;
	int k;

	ready(&u);
	for (k = 0; k < 10; k++) {
		measure(0, &s);
		assert_int_equal(s.a[2], 2047);
		assert_true(s.a[0] > -50 && s.a[0] < 50);
	}
}

static void test_fault_nak(void **state)
{
	struct as9888_unit u = unit_fault(AS9888_FAULT_NAK);
	int k, fails = 0;
	u8 v;

	T = 1 * MSEC;
	as9888_model_init(&M, &u, T);
	at(AS9888_T_BOOT_NS);
	for (k = 1; k <= 200; k++) {
		int ret = as9888_model_read(&M, T, AS9888_REG_WIA, &v, 1);

		if (k % 50 == 0) {
			assert_int_equal(ret, -EIO);
			fails++;
		} else {
			assert_int_equal(ret, 0);
			assert_int_equal(v, 0x48);
		}
	}
	assert_int_equal(fails, 4);
	assert_int_equal(M.stats.naks, 4);
	/* writes count too */
	for (k = 1; k <= 49; k++)
		assert_int_equal(as9888_model_write(&M, T, 2, &v, 1), 0);
	assert_int_equal(as9888_model_write(&M, T, 2, &v, 1), -EIO);
}

static void test_fault_selftest_weak(void **state)
{
	struct as9888_unit u = unit_fault(AS9888_FAULT_SELFTEST_WEAK);
	struct sample s;
	double adj;

	u.field_nt[0] = u.field_nt[1] = u.field_nt[2] = 0;
	ready(&u);
	measure_mode(0, AS9888_MS_SELF_TEST, &s);
	adj = s.h[2] * (u.eeprom[6] + 128) / 256.0;
	assert_true(fabs(adj - 150) < 1.1);
	assert_true(fabs(s.h[0] * (u.eeprom[4] + 128) / 256.0 + 20) < 1.1);
	/* normal measurements are unaffected */
	u.field_nt[2] = -40000;
	ready(&u);
	measure(AS9888_SLCT2_MEN_MSK, &s);
	expect_raw(ref_mag(&u, 2, 0), s.h[2], -4096, 4095);
}

static void test_fault_hofl(void **state)
{
	struct as9888_unit u = unit_fault(AS9888_FAULT_HOFL);
	struct sample s;

	ready(&u);
	measure(AS9888_SLCT2_MEN_MSK, &s);
	assert_int_equal(s.st2 & AS9888_ST2_HOFL_MSK, AS9888_ST2_HOFL_MSK);
	assert_int_equal(s.h[0], 4095);
	measure_mode(0, AS9888_MS_SELF_TEST, &s);
	assert_int_equal(s.st2 & AS9888_ST2_HOFL_MSK, AS9888_ST2_HOFL_MSK);
	measure(0, &s);
	assert_int_equal(s.st2, AS9888_ST2_HST_MSK);
}

/* ---- counters and robustness ---- */

static void test_stats(void **state)
{
	const struct as9888_model_stats *st;
	struct sample s;
	u8 v;

	T = 0;
	as9888_model_init(&M, NULL, T);
	assert_int_equal(as9888_model_read(&M, T, 0, &v, 1), -EIO);
	at(AS9888_T_BOOT_NS);
	wr(AS9888_REG_INT1EN, 1);
	measure(0, &s);
	st = as9888_model_stats(&M);
	/* read (NAK), INT1EN, SLCT2, MS, 2 x MS read, burst */
	assert_int_equal(st->transfers, 7);
	assert_int_equal(st->reads, 4);
	assert_int_equal(st->writes, 3);
	assert_int_equal(st->naks, 1);
	assert_int_equal(st->bytes_read, 2 + 16);
	assert_int_equal(st->bytes_written, 3);
	assert_int_equal(st->measurements, 1);
}

static void test_random_access_no_ub(void **state)
{
	struct as9888_unit u = unit_default();
	u64 x = 88172645463325252ULL;
	struct sample s;
	u8 buf[40];
	int k;

	u.faults = AS9888_FAULT_ALL & ~AS9888_FAULT_RSTN_OPEN;
	u.drift_udegc_s = 100000000;
	ready(&u);
	for (k = 0; k < 200000; k++) {
		u8 reg, len;

		x ^= x << 13;
		x ^= x >> 7;
		x ^= x << 17;
		reg = x & 0xff;
		len = (x >> 8) % sizeof(buf);
		T += (x >> 20) % 400000;
		buf[0] = x >> 32;
		buf[1] = x >> 40;
		switch ((x >> 48) & 7) {
		case 0:
		case 1:
		case 2:
			as9888_model_read(&M, T, reg, buf, len);
			break;
		case 3:
		case 4:
			as9888_model_write(&M, T, (x >> 56) & 1 ? reg : 8,
					   buf, 1 + (len & 1));
			break;
		case 5:
			as9888_model_set_rstn(&M, T, (x >> 56) & 1);
			break;
		default:
			as9888_model_pin(&M, T, (x >> 56) & 1);
			break;
		}
	}
	/* extreme units are clamped, not overflowing */
	u.temperature_mdegc = INT32_MIN;
	u.offset_mlsb[0] = INT32_MAX;
	u.offset_mlsb[1] = INT32_MIN;
	u.up[0] = INT32_MIN;
	u.field_nt[2] = INT32_MAX;
	u.noise_mlsb = UINT32_MAX;
	u.faults = 0;
	memset(u.eeprom, 0xff, 21);
	ready(&u);
	measure(AS9888_SLCT2_MEN_MSK, &s);
	assert_int_equal(s.a[0], 2047);
	assert_int_equal(s.a[1], -2048);
	assert_int_equal(s.h[2], 4095);
	assert_int_equal(s.st2, AS9888_ST2_HOFL_MSK);
	assert_int_equal(s.tmps, 255);
	assert_int_equal(as9888_model_accel_nlsb(&M, 7, 0), 0);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_register_addresses),
		cmocka_unit_test(test_wia),
		cmocka_unit_test(test_reset_values),
		cmocka_unit_test(test_rw_registers),
		cmocka_unit_test(test_unlisted_registers),
		cmocka_unit_test(test_readonly_registers),
		cmocka_unit_test(test_empt_zero),
		cmocka_unit_test(test_mode_single),
		cmocka_unit_test(test_mode_eeprom_enter_leave),
		cmocka_unit_test(test_mode_self_test),
		cmocka_unit_test(test_mode_ignored_not_from_pd),
		cmocka_unit_test(test_mode_ignored_before_tpd),
		cmocka_unit_test(test_mode_ignored_before_tpd_after_auto_return),
		cmocka_unit_test(test_mode_power_on_entry_tpd),
		cmocka_unit_test(test_mode_reserved_ignored),
		cmocka_unit_test(test_mode_ignored_write_changes_nothing),
		cmocka_unit_test(test_mode_zero_aborts),
		cmocka_unit_test(test_mode_zero_abort_starts_tpd),
		cmocka_unit_test(test_mode_accepted_write_deasserts),
		cmocka_unit_test(test_mode_zero_in_pd_deasserts),
		cmocka_unit_test(test_int_rise_enabled),
		cmocka_unit_test(test_intst_read_deasserts),
		cmocka_unit_test(test_int_stays_after_st2),
		cmocka_unit_test(test_st2_clears_drdy_dor),
		cmocka_unit_test(test_dor),
		cmocka_unit_test(test_dor_not_set_when_read),
		cmocka_unit_test(test_hst),
		cmocka_unit_test(test_hofl_saturation),
		cmocka_unit_test(test_burst_read_sample),
		cmocka_unit_test(test_burst_write_auto_increment),
		cmocka_unit_test(test_burst_read_auto_increment),
		cmocka_unit_test(test_burst_crossing_regions),
		cmocka_unit_test(test_burst_wraps),
		cmocka_unit_test(test_burst_write_trim),
		cmocka_unit_test(test_trim_only_in_pd),
		cmocka_unit_test(test_ga_bit7_reads_zero),
		cmocka_unit_test(test_eeprom_hidden_before_teep),
		cmocka_unit_test(test_eeprom_visible_after_teep),
		cmocka_unit_test(test_eeprom_hidden_other_modes),
		cmocka_unit_test(test_eeprom_teep_restarts),
		cmocka_unit_test(test_reset_pulse),
		cmocka_unit_test(test_reset_short_pulse_ignored),
		cmocka_unit_test(test_power_off_on),
		cmocka_unit_test(test_unpowered_access_counted),
		cmocka_unit_test(test_magn_measurements_counted),
		cmocka_unit_test(test_peek_no_side_effects),
		cmocka_unit_test(test_reset_boot_nak),
		cmocka_unit_test(test_power_on_boot_nak),
		cmocka_unit_test(test_spi_boot_reads_ff),
		cmocka_unit_test(test_reset_aborts_measurement),
		cmocka_unit_test(test_reset_takes_effect_after_trstl),
		cmocka_unit_test(test_duration_acc),
		cmocka_unit_test(test_duration_acc_lpf),
		cmocka_unit_test(test_duration_mag),
		cmocka_unit_test(test_duration_self_test),
		cmocka_unit_test(test_slct2_sampled_at_start),
		cmocka_unit_test(test_time_never_decreases),
		cmocka_unit_test(test_tmps_values),
		cmocka_unit_test(test_tmps_drift),
		cmocka_unit_test(test_tmps_every_measurement),
		cmocka_unit_test(test_accel_default_unit),
		cmocka_unit_test(test_accel_units),
		cmocka_unit_test(test_accel_kote_fallback),
		cmocka_unit_test(test_accel_dac_effect),
		cmocka_unit_test(test_accel_gain_register),
		cmocka_unit_test(test_accel_untrimmed),
		cmocka_unit_test(test_accel_ref3_wrong),
		cmocka_unit_test(test_accel_clamped),
		cmocka_unit_test(test_rounding_ties_to_even),
		cmocka_unit_test(test_mag_values),
		cmocka_unit_test(test_mag_self_test),
		cmocka_unit_test(test_mag_self_test_keeps_accel),
		cmocka_unit_test(test_noise_rms),
		cmocka_unit_test(test_noise_rms_alpf),
		cmocka_unit_test(test_noise_zero),
		cmocka_unit_test(test_noise_seed_determinism),
		cmocka_unit_test(test_live_temperature),
		cmocka_unit_test(test_live_up),
		cmocka_unit_test(test_live_noise),
		cmocka_unit_test(test_world_earth_heading),
		cmocka_unit_test(test_world_orientation_moves_accel),
		cmocka_unit_test(test_world_iron),
		cmocka_unit_test(test_world_disturbance),
		cmocka_unit_test(test_world_noise),
		cmocka_unit_test(test_world_tumble),
		cmocka_unit_test(test_fault_no_drdy),
		cmocka_unit_test(test_fault_int1_open),
		cmocka_unit_test(test_pin_rises_between_looks),
		cmocka_unit_test(test_fault_int2_open),
		cmocka_unit_test(test_fault_rstn_open),
		cmocka_unit_test(test_fault_wia),
		cmocka_unit_test(test_fault_eeprom_blank),
		cmocka_unit_test(test_fault_stuck_x),
		cmocka_unit_test(test_fault_saturate_z),
		cmocka_unit_test(test_fault_nak),
		cmocka_unit_test(test_fault_selftest_weak),
		cmocka_unit_test(test_fault_hofl),
		cmocka_unit_test(test_stats),
		cmocka_unit_test(test_random_access_no_ub),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
