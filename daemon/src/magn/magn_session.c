// SPDX-License-Identifier: GPL-2.0
/* The explicit magnetometer calibration session (magn_session.h). */
#include <errno.h>
#include <math.h>
#include <string.h>

#include "iio_mount.h"
#include "magn/magn_capture.h"
#include "magn/magn_session.h"

#define NS_PER_S	1000000000ULL
#define NT_PER_UT	1000.0
#define MICRO		1000000.0
/* The chip's axes by name */
#define AXIS_NAMES	"XYZ"

/* the capture delivers a sample's measurements in one interval */
_Static_assert(MAGN_CAPTURE_RATE_HZ * MAGN_SESSION_INTERVAL_NS ==
	       MAGN_SOURCE_AVERAGE * NS_PER_S,
	       "MAGN_SOURCE_AVERAGE pairs of the capture per session interval");

/* magcal's configuration of a session: its own drift limit, the site's field */
static void session_config(struct magcal_config *cfg, double earth_ut)
{
	magcal_config_default(cfg);
	cfg->max_drift_ut = MAGN_SESSION_MAX_DRIFT_UT;
	cfg->reference_field_ut = earth_ut;
}

double magn_session_coverage(bool averaged)
{
	return averaged ? MAGN_SESSION_COVERAGE : MAGN_SESSION_COVERAGE_SINGLE;
}

bool magn_session_done(const struct magcal_result *fit, bool averaged)
{
	return fit->status == MAGCAL_OK &&
	       fit->coverage >= magn_session_coverage(averaged);
}

int magn_session_hint(const struct magcal_session *fit, const double m_ut[3],
		      const double (*mount)[AS9888_AXES], struct magn_hint *h)
{
	double chip[AS9888_AXES], axis[AS9888_AXES], deg;
	int i, ret;

	ret = magcal_guide(fit, m_ut, chip, &deg);
	if (ret)
		return ret;
	/* a turn's axis is a vector: the mount matrix takes it over */
	if (mount)
		iio_mount_apply(mount, chip, axis);
	else
		memcpy(axis, chip, sizeof(axis));
	h->device = mount != NULL;
	h->axis = 0;
	for (i = 1; i < AS9888_AXES; i++)
		if (fabs(axis[i]) > fabs(axis[h->axis]))
			h->axis = i;
	h->sign = axis[h->axis] < 0 ? -1 : 1;
	h->deg = deg;

	return 0;
}

void magn_hint_text(const struct magn_hint *h, char *buf, size_t size)
{
	static const char name[] = AXIS_NAMES;
	int from = (h->axis + 1) % AS9888_AXES, to = (h->axis + 2) % AS9888_AXES;

	snprintf(buf, size, "turn it about the %s's %c axis, +%c toward %c%c, about %.0f deg",
		 h->device ? "device" : "chip", name[h->axis], name[from],
		 h->sign > 0 ? '+' : '-', name[to], h->deg);
}

/*
 * A progress line: the coverage and where to turn next, in the device's
 * axes where the source knows them
 */
static void say_progress(const struct magcal_session *fit,
			 struct magn_source *src, const struct magn_reading *r,
			 FILE *progress)
{
	double mount[AS9888_AXES][AS9888_AXES];
	bool device = magn_source_mount(src, mount);
	struct magn_hint h;
	char hint[MAGN_HINT_TEXT_MAX];

	fprintf(progress, "coverage %3.0f%%, %u samples kept",
		100 * magcal_progress(fit), magcal_count(fit));
	if (!magn_session_hint(fit, r->field_ut,
			       device ? (const double (*)[AS9888_AXES])mount :
					NULL, &h)) {
		magn_hint_text(&h, hint, sizeof(hint));
		fprintf(progress, "; to cover more: %s", hint);
	}
	fputc('\n', progress);
	fflush(progress);
}

/* Try a fit; true when its quality is reached */
static bool try_solve(struct magcal_session *fit, struct magn_session_result *res)
{
	if (magcal_solve(fit, &res->fit))
		return false;
	res->solved = true;

	return magn_session_done(&res->fit, res->averaged);
}

/*
 * Wait for the next sample's time, @tick (advanced): paced by the clock,
 * not by the reads, whose measurements can take most of the interval on
 * the chip's registers (the capture paces itself: its sleep returns). A
 * late sample starts the next interval: no catching up in a burst.
 */
static uint64_t pace(struct magn_source *src, uint64_t *tick)
{
	uint64_t now = magn_source_now_ns(src);

	*tick += MAGN_SESSION_INTERVAL_NS;
	if (*tick > now)
		magn_source_sleep(src, *tick - now);
	else
		*tick = now;

	return magn_source_now_ns(src);
}

/*
 * The field drifting now (a fit the gate refused): said once while it
 * lasts, so the user can step away from what moves; true while it does
 */
static bool warn_drift(const struct magn_session_result *res, bool warned,
		       FILE *progress)
{
	bool drifting = res->fit.status == MAGCAL_INCONSISTENT;

	if (drifting && !warned && progress) {
		fprintf(progress, "the field is changing (a magnet or steel moving nearby?): move away from it and keep turning; what it changed is replaced as you cover its directions again\n");
		fflush(progress);
	}
	return drifting;
}

int magn_session_run(struct magn_source *src, uint64_t timeout_ns,
		     double earth_ut, FILE *progress,
		     struct magn_session_result *res, char *err, size_t errlen)
{
	struct magcal_session *fit;
	struct magcal_config cfg;
	uint64_t start = magn_source_now_ns(src), now = start, tick = start;
	unsigned int kept = 0, next_solve = MAGN_SESSION_SOLVE_EVERY;
	unsigned int next_progress = MAGN_SESSION_PROGRESS_EVERY;
	unsigned int next_line = MAGN_SESSION_PROGRESS_SAMPLES;
	struct magn_reading r;
	bool warned = false;
	int ret = -ETIMEDOUT;

	memset(res, 0, sizeof(*res));
	res->averaged = true;
	session_config(&cfg, earth_ut);
	fit = magcal_new(&cfg);
	if (!fit && earth_ut) {
		/* the one configuration this session changes */
		snprintf(err, errlen, "the site's field %.3f uT is not the Earth's (%.0f..%.0f uT), or out of memory",
			 earth_ut, cfg.field_min_ut, cfg.field_max_ut);
		return -EINVAL;
	}
	if (!fit) {
		snprintf(err, errlen, "out of memory");
		return -ENOMEM;
	}
	while (now - start < timeout_ns) {
		int got = magn_source_read(src, &r, err, errlen);

		res->samples++;
		if (got == -ERANGE) {
			res->overflows++;
		} else if (got) {
			ret = got;
			break;
		} else if (magcal_add(fit, r.field_ut, r.accel) > 0) {
			kept++;
			/* one noisier sample kept: the session needs more */
			if (r.measurements < MAGN_SOURCE_AVERAGE)
				res->averaged = false;
		}
		if (progress && !got && (kept >= next_progress ||
					 res->samples >= next_line)) {
			next_progress = kept + MAGN_SESSION_PROGRESS_EVERY;
			next_line = res->samples + MAGN_SESSION_PROGRESS_SAMPLES;
			say_progress(fit, src, &r, progress);
		}
		if (kept >= next_solve) {
			next_solve = kept + MAGN_SESSION_SOLVE_EVERY;
			if (try_solve(fit, res)) {
				ret = 0;
				break;
			}
			warned = warn_drift(res, warned, progress);
		}
		now = pace(src, &tick);
	}
	/*
	 * Out of time: the last word is a fit of everything kept, held to the
	 * same rule as every fit before it. magcal's own floor (40 %) is not
	 * enough: the session's coverage is part of the gate's margin
	 * (docs/DECISIONS.md), and a fit taken below it can be degrees off.
	 */
	if (ret == -ETIMEDOUT && magcal_count(fit) && try_solve(fit, res))
		ret = 0;
	if (!ret && progress &&
	    res->fit.turn_deg >= MAGN_SESSION_TURN_NOTE_DEG) {
		fprintf(progress, "the magnetometer reads the field turned by %.1f deg against the accelerometer (an asymmetric soft iron): %s\n",
			res->fit.turn_deg, res->fit.turn_trusted ?
			"the turn is corrected" :
			"not determined well enough to correct, headings can be off by about as much");
		fflush(progress);
	}
	res->coverage = magcal_progress(fit);
	res->elapsed_ns = magn_source_now_ns(src) - start;
	magcal_free(fit);

	return ret;
}

void magn_session_why(const struct magn_session_result *res, char *buf,
		      size_t size)
{
	const struct magcal_result *f = &res->fit;
	struct magcal_config cfg;

	if (!res->solved || f->status == MAGCAL_NO_COVERAGE ||
	    (f->status == MAGCAL_OK && !magn_session_done(f, res->averaged))) {
		snprintf(buf, size, "not enough orientations covered (%.0f%% in %.0f s, %u samples): turn the device slowly through every direction (a figure eight, then over on every side) and run again",
			 /* what was judged: the last fit's, when there was one */
			 100 * (res->solved ? f->coverage : res->coverage),
			 res->elapsed_ns / (double)NS_PER_S,
			 res->samples);
		return;
	}
	switch (f->status) {
	case MAGCAL_FIELD_IMPLAUSIBLE:
		snprintf(buf, size, "the fitted field, %.1f uT, is not the Earth's (20..70 uT): a magnet or steel close to the device? Move away from it and run again",
			 f->fitted_field_ut);
		break;
	case MAGCAL_RESIDUAL_HIGH:
		snprintf(buf, size, "the samples do not fit one field (residual %.2f uT rms, %u rejected): a disturbance during the session (a magnet or moving metal nearby); run again away from it",
			 f->residual_ut, f->rejected);
		break;
	case MAGCAL_INCONSISTENT:
		session_config(&cfg, 0);
		snprintf(buf, size, "the field changed during the session (its strength drifted by %.2f uT, its dip by %.2f deg beyond the noise; at most %.2f uT and %.2f deg are taken): a magnet or steel moving slowly near the device; run again away from it",
			 f->drift_ut, f->dip_drift_deg, cfg.max_drift_ut,
			 cfg.max_dip_drift_deg);
		break;
	default:
		snprintf(buf, size, "the fit failed (%s): run again, turning the device through every direction",
			 magcal_status_str(f->status));
		break;
	}
}

int magn_session_to_record(const struct magcal_result *fit, int64_t now,
			   struct calib_magn *m, char *err, size_t errlen)
{
	int i, j;

	memset(m, 0, sizeof(*m));
	m->present = true;
	for (i = 0; i < AS9888_AXES; i++) {
		if (fabs(fit->bias[i]) > RECORD_MAGN_BIAS_MAX_NT / NT_PER_UT) {
			snprintf(err, errlen, "hard iron %.1f uT on axis %c is beyond +-1000 uT",
				 fit->bias[i], AXIS_NAMES[i]);
			return -ERANGE;
		}
		m->hard_iron_nt[i] = (int32_t)lrint(fit->bias[i] * NT_PER_UT);
		/* symmetric as the record requires: the mean of both halves */
		for (j = 0; j < AS9888_AXES; j++)
			m->soft_iron_micro[i][j] = (int32_t)lrint(
				(fit->w[i][j] + fit->w[j][i]) / 2 * MICRO);
	}
	m->field_nt = (int32_t)lrint(fit->field_ut * NT_PER_UT);
	m->residual_nt = (int32_t)lrint(fit->residual_ut * NT_PER_UT);
	m->coverage_milli = (int32_t)lrint(fit->coverage * 1000);
	m->samples = fit->used;
	m->learned = now;
	/* the soft iron's turn: the identity unless magcal trusts it */
	m->has_rotation = true;
	for (i = 0; i < AS9888_AXES; i++)
		for (j = 0; j < AS9888_AXES; j++)
			m->rotation_micro[i][j] = fit->turn_trusted ?
				(int32_t)lrint(fit->rot[i][j] * MICRO) :
				(i == j) * (int32_t)MICRO;

	return record_magn_validate(m, err, errlen) ? -ERANGE : 0;
}
