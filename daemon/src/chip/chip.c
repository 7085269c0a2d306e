// SPDX-License-Identifier: GPL-2.0
/* Chip operations over a transport (see chip.h). */
#include <errno.h>
#include <string.h>

#include "as9888_regs.h"
#include "chip/chip.h"

#define NS_PER_US		1000ULL
/* Time allowed beyond the datasheet's conversion time before giving up */
#define CHIP_TIMEOUT_MARGIN_US	5000
/* Pause between two ST1 polls; a poll itself takes a bus transfer */
#define CHIP_POLL_INTERVAL_US	50

void chip_init(struct chip *c, struct transport *t)
{
	memset(c, 0, sizeof(*c));
	c->t = t;
	c->use_int1 = t->ops->pin_monitored(t, TRANSPORT_INT1);
}

int chip_reset(struct chip *c)
{
	struct transport *t = c->t;
	int ret;

	c->int1_dr = false;
	c->powered_down = false;
	ret = t->ops->set_rstn(t, false);
	if (ret)
		return ret;
	transport_sleep_ns(t, AS9888_T_RSTL_US * NS_PER_US);
	ret = t->ops->set_rstn(t, true);
	if (ret)
		return ret;
	transport_sleep_ns(t, AS9888_T_BOOT_US * NS_PER_US);
	/* a reset enters power-down at the rising edge: t_PD is covered */
	c->pd_since_ns = transport_now_ns(t) - AS9888_T_PD_US * NS_PER_US;
	c->powered_down = true;

	return 0;
}

int chip_set_mode(struct chip *c, uint8_t ms)
{
	struct transport *t = c->t;
	int ret;

	if (ms != AS9888_MS_POWER_DOWN) {
		uint64_t ready = c->pd_since_ns + AS9888_T_PD_US * NS_PER_US;
		uint64_t now = transport_now_ns(t);

		if (now < ready)
			transport_sleep_ns(t, ready - now);
	}

	c->powered_down = false;
	ret = transport_write_reg(t, AS9888_REG_MS, ms);
	if (ret)
		return ret;
	if (ms == AS9888_MS_POWER_DOWN) {
		c->pd_since_ns = transport_now_ns(t);
		c->powered_down = true;
	}

	return 0;
}

static int chip_poll_drdy(struct chip *c, uint64_t deadline, bool *ready)
{
	struct transport *t = c->t;
	uint8_t st1;
	int ret;

	*ready = false;
	for (;;) {
		/*
		 * The time before the read: a read that started after the
		 * deadline is the last one, whatever delayed us since
		 */
		bool last = transport_now_ns(t) >= deadline;

		ret = transport_read_reg(t, AS9888_REG_ST1, &st1);
		if (ret)
			return ret;
		if (st1 & AS9888_ST1_DRDY_MSK) {
			*ready = true;
			return 0;
		}
		if (last)
			return 0;
		transport_sleep_ns(t, CHIP_POLL_INTERVAL_US * NS_PER_US);
	}
}

int chip_start(struct chip *c, uint8_t ms, uint64_t duration_us)
{
	int ret;

	c->timeout_ns = (duration_us + CHIP_TIMEOUT_MARGIN_US) * NS_PER_US;
	ret = chip_set_mode(c, ms);
	if (ret)
		return ret;
	c->started_ns = transport_now_ns(c->t);

	return 0;
}

int chip_wait(struct chip *c, enum chip_wait *how)
{
	struct transport *t = c->t;
	uint64_t deadline = c->started_ns + c->timeout_ns, now;
	bool ready;
	int ret;

	if (c->use_int1) {
		now = transport_now_ns(t);
		ret = t->ops->wait_pin(t, TRANSPORT_INT1,
				       deadline > now ? deadline - now : 0);
		if (ret < 0)
			return ret;
		if (ret > 0) {
			*how = CHIP_WAIT_INT1;
			/* the chip went back to power-down at the latest now */
			c->pd_since_ns = transport_now_ns(t);
			c->powered_down = true;
			return 0;
		}
		/* INT1 stayed low: let DRDY tell whether the chip finished */
		deadline = transport_now_ns(t);
	}

	ret = chip_poll_drdy(c, deadline, &ready);
	if (ret)
		return ret;
	*how = ready ? CHIP_WAIT_DRDY : CHIP_WAIT_TIMEOUT;
	if (ready) {
		c->pd_since_ns = transport_now_ns(t);
		c->powered_down = true;
	} else {
		/* abort whatever runs, so the chip is in power-down again */
		ret = chip_set_mode(c, AS9888_MS_POWER_DOWN);
		if (ret)
			return ret;
	}

	return 0;
}

int chip_measure(struct chip *c, uint8_t ms, uint64_t duration_us,
		 enum chip_wait *how)
{
	int ret;

	ret = chip_start(c, ms, duration_us);

	return ret ? ret : chip_wait(c, how);
}

static int16_t le16(const uint8_t *p)
{
	return (int16_t)(uint16_t)(p[0] | p[1] << 8);
}

static void decode_sample(const uint8_t buf[AS9888_SAMPLE_LEN],
			  struct chip_sample *s)
{
	int axis;

	for (axis = 0; axis < CHIP_AXES; axis++) {
		s->mag[axis] = le16(&buf[AS9888_REG_HXL - AS9888_REG_ST1 + 2 * axis]);
		s->acc[axis] = le16(&buf[AS9888_REG_A1XL - AS9888_REG_ST1 + 2 * axis]);
	}
	s->tmps = buf[AS9888_REG_TMPS - AS9888_REG_ST1];
	s->empt = buf[AS9888_REG_EMPT - AS9888_REG_ST1];
	s->st2 = buf[AS9888_REG_ST2 - AS9888_REG_ST1];
}

/*
 * The registers the application note reads for a sample, no more: ST1,
 * then the magnetometer data (step 2) or TMPS, EMPT and the accelerometer
 * data (step 3), then ST2; the bytes between that it does not read are
 * skipped (one more transaction, fewer bus bits)
 */
int chip_read_sample(struct chip *c, bool men, struct chip_sample *s)
{
	uint8_t buf[AS9888_SAMPLE_LEN];
	int ret;

	memset(buf, 0, sizeof(buf));
	if (men) {
		ret = transport_read(c->t, AS9888_REG_ST1, buf,
				     AS9888_REG_HXL + 6 - AS9888_REG_ST1);
		if (!ret)
			ret = transport_read(c->t, AS9888_REG_ST2,
					     &buf[AS9888_REG_ST2 - AS9888_REG_ST1], 1);
	} else {
		ret = transport_read(c->t, AS9888_REG_ST1, buf, 1);
		if (!ret)
			ret = chip_read_rest(c, s);
		if (!ret)
			s->st1 = buf[0];
		return ret;
	}
	if (ret)
		return ret;

	s->st1 = buf[0];
	decode_sample(buf, s);

	return 0;
}

int chip_read_rest(struct chip *c, struct chip_sample *s)
{
	uint8_t buf[AS9888_SAMPLE_LEN];
	int ret;

	memset(buf, 0, sizeof(buf));
	ret = transport_read(c->t, AS9888_REG_TMPS,
			     &buf[AS9888_REG_TMPS - AS9888_REG_ST1],
			     AS9888_REG_ST2 - AS9888_REG_TMPS + 1);
	if (!ret)
		decode_sample(buf, s);

	return ret;
}

int chip_read_overlapped(struct chip *c, struct chip_sample *s, bool *newer)
{
	uint8_t buf[AS9888_SAMPLE_LEN];
	int ret;

	ret = transport_read(c->t, AS9888_REG_ST1, buf, sizeof(buf));
	if (ret)
		return ret;
	*newer = buf[0] & AS9888_ST1_DRDY_MSK;
	decode_sample(buf, s);

	return 0;
}

uint64_t chip_measure_time_us(bool men, bool alpf)
{
	if (men)
		return AS9888_T_MAG_US;
	return alpf ? AS9888_T_ACC_LPF_US : AS9888_T_ACC_US;
}
