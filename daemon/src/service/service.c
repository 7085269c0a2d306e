// SPDX-License-Identifier: GPL-2.0
/*
 * "as9888-calibd daemon": the long-running service. It sleeps in poll()
 * until something happens (no periodic wake-up):
 * - a kernel uevent says an AS9888 IIO device appeared (boot, module
 *   reload, rebind): the record is applied to it;
 * - a client on the Unix socket asks for status, check, recalibrate,
 *   rollback or magn (the magnetometer's calibration; request.h): the request runs in a child process whose output
 *   goes to the client;
 * - SIGTERM, SIGINT or SIGHUP: it stops (see stop()).
 *
 * No client can stall it or anyone else: a client's connection is read
 * without blocking and has REQUEST_DEADLINE_MS from connecting to send its
 * whole request line; status runs at once whatever else is running; the
 * requests that use the chip or write the record (and the application on
 * a device's appearance) run one at a time, in the order they came, each
 * in its own child, while the loop goes on. At most CLIENTS_MAX clients
 * are served at once; more are told "busy". No user can take them all:
 * each user but root holds at most CLIENTS_PER_UID connections, and all of
 * them together leave CLIENTS_ROOT_RESERVED to root; a user over its share
 * loses its oldest connection that has not sent its request line yet (the
 * idle one) to the new one, or is told "busy". SIGPIPE is ignored: a
 * client that hangs up only loses its answer.
 * Who may connect is decided by the socket's file permissions: every
 * client may ask for status, magn and magn-feed (a consumer's requests);
 * check, recalibrate and rollback only root and the members of the
 * operator group (--operator-group; request_for_operator()). Requests that
 * change the record take a change from a budget (record_budget.h) when
 * they start, failed or not, and are refused when it is spent; their
 * requester is named in every log line
 * about them. Routine lines (requests of consumers, refusals) are bounded
 * (log_limit.h), so a flood cannot push those lines out of the journal.
 */
#include <errno.h>
#include <grp.h>
#include <limits.h>
#include <poll.h>
#include <signal.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/signalfd.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "commands/commands.h"
#include "common/fd_close.h"
#include "chip/iio.h"
#include "common/log_limit.h"
#include "store/record_budget.h"
#include "common/request.h"
#include "service/request_reply.h"
#include "service/service_socket.h"
#include "commands/session.h"
#include "service/uevent.h"

/* Clients connected at once (reading, waiting or being served) */
#define CLIENTS_MAX		32
/* What one user other than root may hold of them, and what root keeps */
#define CLIENTS_PER_UID		4
#define CLIENTS_ROOT_RESERVED	8
/* Connections taken per round of the loop: a flood starves nothing else */
#define ACCEPTS_PER_ROUND	64
/* Clients refused as busy are logged at most this often, with their count */
#define REFUSAL_LOG_MS		10000
/* A client has this long from connecting to send its whole request line */
#define REQUEST_DEADLINE_MS	5000
/*
 * After SIGTERM, running requests get this long to finish (a recalibration
 * takes at most its stability timeout, the lock timeout and the
 * measurement); then they are killed, which the record survives.
 */
#define STOP_GRACE_MS		60000
#define EXIT_STATUS_USAGE	2

enum client_state {
	CLIENT_FREE = 0,
	CLIENT_READING,		/* its request line is not complete */
	CLIENT_WAITING,		/* for the chip, in arrival order */
	CLIENT_RUNNING,		/* its child runs the request */
};

struct client {
	enum client_state state;
	int fd;
	uint64_t deadline_ms;		/* of the request line */
	uint64_t arrival;		/* order of the wait for the chip */
	char line[REQUEST_LINE_MAX];
	size_t len;
	struct request req;
	char peer[PEER_DESC_LEN];
	uid_t uid;
	bool operator;			/* root, or in the operator group */
	uint64_t seq;			/* order of connection */
	pid_t pid;
};

struct service {
	const struct cli_opts *o;
	struct service_socket sock;
	int uevent_fd;
	int signal_fd;
	struct client clients[CLIENTS_MAX];
	uint64_t arrivals;
	uint64_t connections;
	unsigned long refused;		/* as busy, since the last log line */
	uint64_t refusal_log_ms;
	bool chip_busy;			/* an exclusive child runs */
	bool apply_wanted;		/* a device appeared: apply when the chip is free */
	char apply_dev[IIO_PATH_MAX];
	pid_t apply_pid;
	uint64_t apply_start_us;
	bool stopping;
	uint64_t stop_deadline_ms;
	unsigned long applied;
	unsigned long apply_failures;
	bool have_operator_gid;
	gid_t operator_gid;
	struct record_budget budget;
	struct log_limit routine;	/* consumers' requests, dropped clients */
	struct log_limit refusals;	/* of permission and of the budget */
};

static void log_msg(const char *fmt, ...) __attribute__((format(printf, 1, 2)));

/* stderr goes to the journal under systemd */
static void log_msg(const char *fmt, ...)
{
	va_list ap;

	fputs("as9888-calibd: ", stderr);
	va_start(ap, fmt);
	vfprintf(stderr, fmt, ap);
	va_end(ap);
	fputc('\n', stderr);
}

static uint64_t monotonic_ms(void);

/*
 * A line of a kind a flood can repeat (log_limit.h): logged unless the
 * flood has used the second's share of @l; refusals have a share of their
 * own, so that a flood of status requests cannot hide them
 */
static void log_limited(struct log_limit *l, const char *fmt, ...)
	__attribute__((format(printf, 2, 3)));

static void log_limited(struct log_limit *l, const char *fmt, ...)
{
	unsigned long suppressed;
	va_list ap;

	if (!log_limit_allow(l, monotonic_ms(), &suppressed))
		return;
	if (suppressed)
		log_msg("%lu log line(s) like the next left out (more than %d a second)",
			suppressed, LOG_LIMIT_LINES);
	fputs("as9888-calibd: ", stderr);
	va_start(ap, fmt);
	vfprintf(stderr, fmt, ap);
	va_end(ap);
	fputc('\n', stderr);
}

static uint64_t monotonic_us(void)
{
	struct timespec ts;

	clock_gettime(CLOCK_MONOTONIC, &ts);
	return (uint64_t)ts.tv_sec * 1000000 + (uint64_t)ts.tv_nsec / 1000;
}

static uint64_t monotonic_ms(void)
{
	return monotonic_us() / 1000;
}

static int open_signals(void)
{
	sigset_t set;

	/* a client that hangs up must never kill us: EPIPE instead */
	signal(SIGPIPE, SIG_IGN);
	sigemptyset(&set);
	sigaddset(&set, SIGTERM);
	sigaddset(&set, SIGINT);
	sigaddset(&set, SIGHUP);
	sigaddset(&set, SIGCHLD);
	if (sigprocmask(SIG_BLOCK, &set, NULL))
		return -errno;

	return signalfd(-1, &set, SFD_CLOEXEC | SFD_NONBLOCK);
}

/*
 * A child running @fn; -errno if none. It keeps only @keep (as fd 3, or
 * nothing with -1) and the standard streams of the daemon: the other
 * clients' connections close when the daemon closes them, not when this
 * child ends.
 */
static pid_t spawn(int keep, int (*fn)(int fd, struct service *s, void *arg),
		   struct service *s, void *arg)
{
	sigset_t set;
	pid_t pid;

	fflush(NULL);
	pid = fork();
	if (pid < 0)
		return -errno;
	if (pid)
		return pid;

	sigemptyset(&set);
	sigprocmask(SIG_SETMASK, &set, NULL);
	signal(SIGCHLD, SIG_DFL);
	if (keep >= 0 && keep != 3 && dup2(keep, 3) < 0)
		_exit(EXIT_FAILURE);
	fd_close_from(keep >= 0 ? 4 : 3);
	_exit(fn(3, s, arg));
}

static int request_status(const struct cli_opts *o)
{
	struct cli_opts show = *o;

	show.temperature_given = false;
	return cmd_show(&show);
}

static int (*const request_fn[])(const struct cli_opts *o) = {
	[REQUEST_STATUS] = request_status,
	[REQUEST_CHECK] = cmd_check,
	[REQUEST_RECALIBRATE] = cmd_recalibrate,
	[REQUEST_ROLLBACK] = cmd_rollback,
	[REQUEST_MAGN] = cmd_magn_show,
	[REQUEST_MAGN_FEED] = cmd_magn_feed,
};

static int run_request(int fd, struct service *s, void *arg)
{
	const struct client *c = arg;
	struct cli_opts o = *s->o;

	o.json = c->req.json;
	o.magn_feed = c->req.feed;
	/* the daemon's log, which the reply takes stderr from */
	o.log_fd = dup(STDERR_FILENO);
	o.requester = c->peer;
	return request_reply_run(fd, request_fn[c->req.kind], &o, c->req.json);
}

static int run_apply(int fd, struct service *s, void *arg)
{
	bool simulator = s->o->backend == CLI_BACKEND_SIM;

	return iio_restore(s->o->record_path, s->apply_dev, simulator) ?
	       EXIT_FAILURE : EXIT_SUCCESS;
}

static void client_close(struct client *c)
{
	close(c->fd);
	memset(c, 0, sizeof(*c));
	c->fd = -1;
}

/*
 * Answer @c at once with @text and @status, and let it go. What it sent
 * and we did not read is taken first (a little), so that the hang-up is
 * not a reset that could cost it the answer.
 */
static void client_refuse(struct client *c, const char *text, int status)
{
	char drain[REQUEST_LINE_MAX];
	int i;

	request_reply_status_now(c->fd, text, status);
	shutdown(c->fd, SHUT_WR);
	for (i = 0; i < 4 && recv(c->fd, drain, sizeof(drain), MSG_DONTWAIT) > 0; i++)
		;
	client_close(c);
}

/*
 * A request that changes the record takes a change from the budget, or is
 * refused (told when the next is allowed): false when refused
 */
static bool client_take_budget(struct service *s, struct client *c)
{
	uint64_t wait_ms = record_budget_take(&s->budget, monotonic_ms());
	char text[256];
	unsigned long long min;

	if (!wait_ms)
		return true;
	min = (wait_ms + 59999) / 60000;
	log_limited(&s->refusals, "%s refused for %s: the record's change budget is spent (next in %llu min)",
		    request_name(c->req.kind), c->peer, min);
	snprintf(text, sizeof(text),
		 "error: too many changes of the record: the next is allowed in %llu min (at most %d at once, then one every %llu hours: the flash-wear budget)\n",
		 min, RECORD_BUDGET_BURST,
		 (unsigned long long)(RECORD_BUDGET_REFILL_MS / 3600000));
	client_refuse(c, text, EXIT_FAILURE);

	return false;
}

static void client_start(struct service *s, struct client *c)
{
	const char *name = request_name(c->req.kind);
	pid_t pid;

	if (request_changes_state(c->req.kind)) {
		if (!client_take_budget(s, c))
			return;
		log_msg("%s requested by %s", name, c->peer);
	} else if (!request_quiet(c->req.kind)) {
		log_limited(&s->routine, "%s requested", name);
	}
	pid = spawn(c->fd, run_request, s, c);
	if (pid < 0) {
		/* nothing ran: nothing written */
		if (request_changes_state(c->req.kind))
			record_budget_refund(&s->budget);
		log_msg("%s not run: cannot fork: %s", name, strerror((int)-pid));
		client_refuse(c, "as9888-calibd: the daemon cannot start the request\n",
			      EXIT_FAILURE);
		return;
	}
	c->state = CLIENT_RUNNING;
	c->pid = pid;
	if (request_exclusive(c->req.kind))
		s->chip_busy = true;
}

/* The oldest client waiting for the chip, or NULL */
static struct client *next_waiting(struct service *s)
{
	struct client *next = NULL;
	unsigned int i;

	for (i = 0; i < CLIENTS_MAX; i++) {
		struct client *c = &s->clients[i];

		if (c->state == CLIENT_WAITING && (!next || c->arrival < next->arrival))
			next = c;
	}

	return next;
}

/* The chip to the next in line: a device's appearance first, then clients */
static void run_next(struct service *s)
{
	struct client *c;
	pid_t pid;

	while (!s->chip_busy && !s->stopping) {
		if (s->apply_wanted) {
			s->apply_wanted = false;
			s->apply_start_us = monotonic_us();
			pid = spawn(-1, run_apply, s, NULL);
			if (pid < 0) {
				s->apply_failures++;
				log_msg("calibration not applied to %s: cannot fork: %s",
					s->apply_dev, strerror((int)-pid));
				continue;
			}
			s->apply_pid = pid;
			s->chip_busy = true;
			return;
		}
		c = next_waiting(s);
		if (!c)
			return;
		client_start(s, c);
	}
}

/* @c's request line is complete: run it, queue it, or refuse it */
static void client_dispatch(struct service *s, struct client *c)
{
	char err[160], text[200];

	if (request_parse(c->line, c->len, &c->req, err, sizeof(err))) {
		snprintf(text, sizeof(text), "error: %s\n", err);
		client_refuse(c, text, EXIT_STATUS_USAGE);
		return;
	}
	if (request_for_operator(c->req.kind) && !c->operator) {
		log_limited(&s->refusals, "%s refused for %s: not root nor in the operator group",
			    request_name(c->req.kind), c->peer);
		snprintf(text, sizeof(text),
			 "error: %s is for root and the operator group only; every client may ask for status, magn and magn-feed\n",
			 request_name(c->req.kind));
		client_refuse(c, text, EXIT_FAILURE);
		return;
	}
	if (!request_exclusive(c->req.kind)) {
		client_start(s, c);
		return;
	}
	c->state = CLIENT_WAITING;
	c->arrival = s->arrivals++;
	if (s->chip_busy)
		log_limited(&s->routine, "%s waits for the request before it",
			    request_name(c->req.kind));
	run_next(s);
}

/* Take what @c has sent so far, never blocking */
static void client_read(struct service *s, struct client *c)
{
	char *nl;
	ssize_t n;

	n = recv(c->fd, c->line + c->len, sizeof(c->line) - c->len, MSG_DONTWAIT);
	if (n < 0 && (errno == EAGAIN || errno == EINTR))
		return;
	if (n <= 0) {
		client_refuse(c, "error: the request line ended without a newline\n",
			      EXIT_STATUS_USAGE);
		return;
	}
	c->len += (size_t)n;
	nl = memchr(c->line, '\n', c->len);
	if (nl) {
		c->len = (size_t)(nl - c->line);
		client_dispatch(s, c);
	} else if (c->len == sizeof(c->line)) {
		client_refuse(c, "error: request line too long\n", EXIT_STATUS_USAGE);
	}
}

/* A client refused as busy: counted, and logged now and then */
static void note_refusal(struct service *s, const char *peer)
{
	uint64_t now = monotonic_ms();

	s->refused++;
	if (s->refusal_log_ms && now < s->refusal_log_ms + REFUSAL_LOG_MS)
		return;
	log_msg("%lu client(s) refused as busy in %d s (the last: %s)", s->refused,
		REFUSAL_LOG_MS / 1000, peer);
	s->refused = 0;
	s->refusal_log_ms = now;
}

/*
 * A slot for a new client of @uid: a free one within @uid's share, else
 * the one of a connection still without a request line (the idle one,
 * told busy): @uid's own oldest, or, when the users' slots are all taken,
 * the oldest of the user holding the most of them if that is more than
 * one above @uid's (so that a few users cannot keep out another); NULL
 * when there is none.
 */
static struct client *slot_for(struct service *s, uid_t uid)
{
	struct client *free_slot = NULL, *idle = NULL, *other = NULL;
	unsigned int held[CLIENTS_MAX] = { 0 };
	unsigned int i, j, same = 0, users = 0, most = CLIENTS_MAX;
	bool fits;

	for (i = 0; i < CLIENTS_MAX; i++) {
		struct client *c = &s->clients[i];

		if (c->state == CLIENT_FREE) {
			free_slot = free_slot ? free_slot : c;
			continue;
		}
		users += c->uid != 0;
		/* held[i]: the slots of client i's user, counted at its first */
		for (j = 0; j < i && (s->clients[j].state == CLIENT_FREE ||
				      s->clients[j].uid != c->uid); j++)
			;
		held[j]++;
		if (c->uid != uid)
			continue;
		same++;
		if (c->state == CLIENT_READING && (!idle || c->seq < idle->seq))
			idle = c;
	}
	fits = free_slot && (uid == 0 || (same < CLIENTS_PER_UID &&
		users < CLIENTS_MAX - CLIENTS_ROOT_RESERVED));
	if (fits)
		return free_slot;
	if (!idle && uid != 0 && same < CLIENTS_PER_UID) {
		/* the users' share is full: the biggest holder gives one up */
		/* root's connections are its reserve, never given up */
		for (i = 0; i < CLIENTS_MAX; i++)
			if (s->clients[i].state != CLIENT_FREE && s->clients[i].uid != 0 &&
			    (most == CLIENTS_MAX || held[i] > held[most]))
				most = i;
		for (i = 0; most < CLIENTS_MAX && held[most] > same + 1 &&
		     i < CLIENTS_MAX; i++) {
			struct client *c = &s->clients[i];

			if (c->state == CLIENT_READING && c->uid == s->clients[most].uid &&
			    (!other || c->seq < other->seq))
				other = c;
		}
		idle = other;
	}
	if (!idle)
		return NULL;
	note_refusal(s, idle->peer);
	client_refuse(idle, idle == other ?
		      "error: busy: another user needed a connection and this user held the most; send the request line at once\n" :
		      "error: busy: a newer connection of the same user took this one's place; send the request line at once\n",
		      EXIT_FAILURE);

	return idle;
}

static void accept_clients(struct service *s)
{
	unsigned int n;
	int fd;

	for (n = 0; n < ACCEPTS_PER_ROUND &&
	     (fd = accept4(s->sock.fd, NULL, NULL, SOCK_CLOEXEC)) >= 0; n++) {
		char peer[PEER_DESC_LEN];
		uid_t uid = peer_describe(fd, peer);
		struct client *c = slot_for(s, uid);

		if (!c) {
			struct client busy = { .fd = fd };

			client_refuse(&busy, "error: busy: too many requests at once; try again later\n",
				      EXIT_FAILURE);
			note_refusal(s, peer);
			continue;
		}
		memset(c, 0, sizeof(*c));
		c->fd = fd;
		c->state = CLIENT_READING;
		c->deadline_ms = monotonic_ms() + REQUEST_DEADLINE_MS;
		c->uid = uid;
		c->operator = uid == 0 ||
			      (s->have_operator_gid && peer_in_group(fd, s->operator_gid));
		c->seq = s->connections++;
		memcpy(c->peer, peer, sizeof(c->peer));
		/* a client sends its line with its connection: take it now */
		client_read(s, c);
	}
}

/* Clients past their request line's deadline are let go */
static void expire_clients(struct service *s)
{
	uint64_t now = monotonic_ms();
	unsigned int i;

	for (i = 0; i < CLIENTS_MAX; i++) {
		struct client *c = &s->clients[i];

		if (c->state != CLIENT_READING || now < c->deadline_ms)
			continue;
		log_limited(&s->routine, "client %s dropped: no request line within %d ms",
			    c->peer, REQUEST_DEADLINE_MS);
		client_refuse(c, "error: no request line in time\n", EXIT_STATUS_USAGE);
	}
}

static int exit_status(int wstatus)
{
	return WIFEXITED(wstatus) ? WEXITSTATUS(wstatus) : 128 + WTERMSIG(wstatus);
}

static void apply_done(struct service *s, int wstatus)
{
	s->apply_pid = 0;
	s->chip_busy = false;
	if (exit_status(wstatus)) {
		s->apply_failures++;
		log_msg("calibration not applied to %s", s->apply_dev);
	} else {
		s->applied++;
		log_msg("calibration applied to %s in %llu us", s->apply_dev,
			(unsigned long long)(monotonic_us() - s->apply_start_us));
	}
}

static void client_done(struct service *s, struct client *c, int wstatus)
{
	int status = exit_status(wstatus);

	/* a child that exits has sent its status line itself */
	if (!WIFEXITED(wstatus))
		request_reply_status_now(c->fd, "as9888-calibd: the request was killed\n",
					 status);
	if (request_changes_state(c->req.kind)) {
		/*
		 * A failed request keeps its change taken: one may have written
		 * (a rollback swapped and swapped back, a save cut short)
		 */
		log_msg("%s done: exit status %d (requested by %s)",
			request_name(c->req.kind), status, c->peer);
	} else if (!request_quiet(c->req.kind) || status) {
		log_limited(&s->routine, "%s done: exit status %d",
			    request_name(c->req.kind), status);
	}
	if (request_exclusive(c->req.kind))
		s->chip_busy = false;
	client_close(c);
}

static void reap_children(struct service *s)
{
	unsigned int i;
	int wstatus;
	pid_t pid;

	while ((pid = waitpid(-1, &wstatus, WNOHANG)) > 0) {
		if (pid == s->apply_pid) {
			apply_done(s, wstatus);
			continue;
		}
		for (i = 0; i < CLIENTS_MAX; i++)
			if (s->clients[i].state == CLIENT_RUNNING &&
			    s->clients[i].pid == pid)
				client_done(s, &s->clients[i], wstatus);
	}
	run_next(s);
}

static void handle_uevents(struct service *s)
{
	char buf[UEVENT_BUF_SIZE];
	struct uevent ev;
	char iio[IIO_PATH_MAX];
	ssize_t n;

	while ((n = recv(s->uevent_fd, buf, sizeof(buf), MSG_DONTWAIT)) > 0) {
		if (uevent_parse(buf, (size_t)n, &ev) || !uevent_is_appearance(&ev))
			continue;
		if (iio_find_device(ev.devpath, iio, sizeof(iio)))
			continue;
		snprintf(s->apply_dev, sizeof(s->apply_dev), "%s", iio);
		s->apply_wanted = true;
	}
	run_next(s);
}

static bool children_running(const struct service *s)
{
	unsigned int i;

	for (i = 0; i < CLIENTS_MAX; i++)
		if (s->clients[i].state == CLIENT_RUNNING)
			return true;

	return s->apply_pid > 0;
}

/*
 * A stop signal: no new clients; those not yet running are told; running
 * requests get STOP_GRACE_MS to finish (a record being written is not cut
 * short by us), then are killed.
 */
static void stop(struct service *s, unsigned int signo)
{
	unsigned int i;

	log_msg("signal %u: stopping", signo);
	s->stopping = true;
	s->stop_deadline_ms = monotonic_ms() + STOP_GRACE_MS;
	s->apply_wanted = false;
	for (i = 0; i < CLIENTS_MAX; i++) {
		struct client *c = &s->clients[i];

		if (c->state == CLIENT_READING || c->state == CLIENT_WAITING)
			client_refuse(c, "error: the daemon is stopping\n", EXIT_FAILURE);
	}
}

static void kill_children(struct service *s)
{
	unsigned int i;

	log_msg("requests still running after %d ms: killing them", STOP_GRACE_MS);
	for (i = 0; i < CLIENTS_MAX; i++)
		if (s->clients[i].state == CLIENT_RUNNING)
			kill(s->clients[i].pid, SIGKILL);
	if (s->apply_pid > 0)
		kill(s->apply_pid, SIGKILL);
}

static void handle_signals(struct service *s)
{
	struct signalfd_siginfo si;

	/* SIGCHLD only wakes us: every child that ended is reaped below */
	while (read(s->signal_fd, &si, sizeof(si)) == sizeof(si))
		if (si.ssi_signo != SIGCHLD && !s->stopping)
			stop(s, si.ssi_signo);
	reap_children(s);
}

/* Milliseconds until the nearest deadline, or -1 for none */
static int poll_timeout(const struct service *s)
{
	uint64_t now = monotonic_ms(), next = UINT64_MAX;
	unsigned int i;

	if (s->stopping)
		next = s->stop_deadline_ms;
	for (i = 0; i < CLIENTS_MAX; i++)
		if (s->clients[i].state == CLIENT_READING &&
		    s->clients[i].deadline_ms < next)
			next = s->clients[i].deadline_ms;
	if (next == UINT64_MAX)
		return -1;
	if (next <= now)
		return 0;

	return next - now > INT_MAX ? INT_MAX : (int)(next - now);
}

/* One round of the loop: 1 to go on, 0 when stopped, -1 on failure */
static int serve_once(struct service *s)
{
	struct pollfd fds[3 + CLIENTS_MAX];
	struct client *polled[CLIENTS_MAX];
	nfds_t n = 0, first_client;
	unsigned int i;

	fds[n++] = (struct pollfd){ .fd = s->signal_fd, .events = POLLIN };
	fds[n++] = (struct pollfd){ .fd = s->stopping ? -1 : s->sock.fd, .events = POLLIN };
	fds[n++] = (struct pollfd){ .fd = s->stopping ? -1 : s->uevent_fd, .events = POLLIN };
	first_client = n;
	for (i = 0; i < CLIENTS_MAX; i++)
		if (s->clients[i].state == CLIENT_READING) {
			polled[n - first_client] = &s->clients[i];
			fds[n++] = (struct pollfd){ .fd = s->clients[i].fd, .events = POLLIN };
		}

	if (poll(fds, n, poll_timeout(s)) < 0) {
		if (errno == EINTR)
			return 1;
		log_msg("poll: %s", strerror(errno));
		return -1;
	}
	if (fds[0].revents & POLLIN)
		handle_signals(s);
	if (fds[2].revents & POLLIN)
		handle_uevents(s);
	for (i = first_client; i < n; i++)
		if (fds[i].revents && polled[i - first_client]->state == CLIENT_READING)
			client_read(s, polled[i - first_client]);
	if (fds[1].revents & POLLIN)
		accept_clients(s);
	expire_clients(s);

	if (!s->stopping)
		return 1;
	if (children_running(s) && monotonic_ms() >= s->stop_deadline_ms) {
		kill_children(s);
		s->stop_deadline_ms = UINT64_MAX - 1;
	}
	return children_running(s) ? 1 : 0;
}

/*
 * At start: a change of the record that a crash interrupted is finished or
 * undone before anything reads the record, without waiting for the lock (a
 * command holding it has done that): status is answered at once.
 */
static void recover_record(const struct cli_opts *o)
{
	record_store_recover_now(o->record_path);
}

/* At start: every AS9888 IIO device already there gets its calibration */
static void apply_present(struct service *s)
{
	if (!iio_find_device(NULL, s->apply_dev, sizeof(s->apply_dev))) {
		s->apply_wanted = true;
		run_next(s);
	}
}

int cmd_daemon(const struct cli_opts *o)
{
	struct service s = { .o = o, .uevent_fd = -1 };
	char err[512];
	unsigned int i;
	int ret;

	for (i = 0; i < CLIENTS_MAX; i++)
		s.clients[i].fd = -1;
	if (o->operator_group) {
		struct group *gr = getgrnam(o->operator_group);
		char *end;
		unsigned long gid = strtoul(o->operator_group, &end, 10);

		/* a name, or a number as chown(1) takes one */
		if (!gr && (*end || *o->operator_group < '0' || *o->operator_group > '9' ||
			    gid >= (gid_t)-1)) {
			log_msg("--operator-group %s: no such group", o->operator_group);
			return EXIT_FAILURE;
		}
		s.have_operator_gid = true;
		s.operator_gid = gr ? gr->gr_gid : (gid_t)gid;
	}
	record_budget_init(&s.budget, monotonic_ms());
	/* first: a descriptor passed as fd 3 is checked before we open any */
	if (service_socket_open(o, &s.sock, err, sizeof(err))) {
		log_msg("%s", err);
		return EXIT_FAILURE;
	}
	s.signal_fd = open_signals();
	if (s.signal_fd < 0) {
		log_msg("cannot set up signals: %s", strerror(errno));
		service_socket_close(o, &s.sock);
		return EXIT_FAILURE;
	}
	s.uevent_fd = uevent_open();
	if (s.uevent_fd < 0)
		log_msg("no kernel uevents (%s): devices that appear later are not seen",
			strerror(-s.uevent_fd));

	recover_record(o);
	log_msg("ready: record %s, socket %s, operators: root%s%s", o->record_path,
		o->socket_path, o->operator_group ? " and group " : " only",
		o->operator_group ? o->operator_group : "");
	apply_present(&s);
	while ((ret = serve_once(&s)) > 0)
		;
	/* only a failed poll() leaves with children: they are not waited for */

	service_socket_close(o, &s.sock);
	if (s.uevent_fd >= 0)
		close(s.uevent_fd);
	close(s.signal_fd);
	log_msg("stopped: calibration applied %lu times, %lu failures", s.applied,
		s.apply_failures);

	return ret ? EXIT_FAILURE : EXIT_SUCCESS;
}
