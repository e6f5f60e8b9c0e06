/*
 * Prints CAN frames as `candump` (can-utils) prints them on screen, with the
 * option sets of docs/formats.md#candump-screen, using can-utils' own
 * formatting code (lib.c: snprintf_long_canframe, snprintf_can_error_frame)
 * and the line assembly of candump.c (timestamp, colour, interface, -x
 * columns, -e explanation lines).
 * candump itself needs a CAN socket, which this machine does not have.
 *
 * Usage: driver MODE OUT.txt OUT.json  (MODE: see `modes` below)
 * Writes the screen text and, per printed frame, what the line holds
 * (the truth the crate's reader is tested against).
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <linux/can.h>
#include <linux/can/error.h>
#include "lib.h"
#include "terminal.h"

#define MAXCOL 6
static const char col_on[MAXCOL][19] = { ATTBOLD FGBLUE, ATTBOLD FGRED, ATTBOLD FGGREEN,
					 ATTBOLD, ATTBOLD FGMAGENTA, ATTBOLD FGCYAN };
static const char col_off[] = ATTRESET;
static const char extra_fd_info[4][4] = { "- -", "B -", "- E", "B E" };

struct mode {
	const char *name;
	char timestamp; /* 0, 'a', 'A', 'd', 'z' */
	int use_ns;
	int color;
	int extra; /* -x */
	int view;
};

static const struct mode modes[] = {
	{ "plain", 0, 0, 0, 0, 0 },
	{ "ta_x_e", 'a', 0, 0, 1, CANLIB_VIEW_ERROR },
	{ "tA_a_8", 'A', 0, 0, 0, CANLIB_VIEW_ASCII | CANLIB_VIEW_LEN8_DLC },
	{ "td", 'd', 0, 0, 0, 0 },
	{ "tz_N", 'z', 1, 0, 0, 0 },
	{ "c3_ta", 'a', 0, 3, 0, 0 },
	{ "c1_tA_N_a", 'A', 1, 1, 1, CANLIB_VIEW_ASCII },
	{ "S", 0, 0, 0, 0, CANLIB_VIEW_SWAP },
	{ "i", 0, 0, 0, 0, CANLIB_VIEW_BINARY },
};

/* Frame times: absolute nanoseconds since the epoch; deltas vary up and
 * down, as real traffic's do. */
static const long long base_sec = 1795342272LL; /* 2026-11-22 10:11:12 UTC */
static const long long offsets_ns[] = { 0, 1000500, 1500250, 9000001, 9100000, 20000000,
					20000999, 35123456, 35200000, 50000000, 50000001,
					61000000, 62000000, 70000000 };

static int nframes;
static union cfu frames[16];
static int is_fd[16];
static const char *ifname[16];

static void add_cc(canid_t id, int len, const char *data, int dlc8)
{
	union cfu *cu = &frames[nframes];
	memset(cu, 0, sizeof(*cu));
	cu->cc.can_id = id;
	cu->cc.len = len;
	if (dlc8)
		cu->cc.len8_dlc = dlc8;
	if (data)
		memcpy(cu->cc.data, data, len);
	is_fd[nframes] = 0;
	ifname[nframes] = (nframes % 3 == 2) ? "can1" : "can0";
	nframes++;
}

static void add_fd(canid_t id, int len, unsigned char flags)
{
	union cfu *cu = &frames[nframes];
	memset(cu, 0, sizeof(*cu));
	cu->fd.can_id = id;
	cu->fd.len = len;
	cu->fd.flags = flags | CANFD_FDF;
	for (int i = 0; i < len; i++)
		cu->fd.data[i] = (unsigned char)(i * 7 + 0x20);
	is_fd[nframes] = 1;
	ifname[nframes] = "can0";
	nframes++;
}

static void build(void)
{
	add_cc(0x081, 8, "\x10\x81\x11\x00\x00\x00\x00\x00", 0);
	add_cc(0x705, 1, "\x05", 0);
	add_cc(0x705 | CAN_RTR_FLAG, 1, NULL, 0);
	add_cc(0x123, 0, NULL, 0);
	add_cc(0x385, 8, "Hi Can!'", 0xF);
	add_cc(0x18FF1234 | CAN_EFF_FLAG, 2, "\x01\x02", 0);
	add_cc(0x185, 3, "\x7f\x20\x7e", 0);
	add_fd(0x185, 12, CANFD_BRS);
	add_fd(0x1FFFFFFF | CAN_EFF_FLAG, 64, CANFD_ESI);
	add_fd(0x186, 8, CANFD_BRS | CANFD_ESI);
	add_cc(CAN_ERR_FLAG | CAN_ERR_CRTL, 8, "\x00\x04\x00\x00\x00\x00\x00\x00", 0);
	add_cc(CAN_ERR_FLAG | CAN_ERR_BUSOFF | CAN_ERR_CNT, 8, "\x00\x00\x00\x00\x00\x00\x80\x90", 0);
	add_cc(0x701, 1, "\x7f", 0);
	add_cc(0x000, 2, "\x01\x00", 0);
}

static int sprint_ts(char *out, char timestamp, int use_ns, struct timespec *ts,
		     struct timespec *last_ts, long long *shown_ns)
{
	int n = 0;
	switch (timestamp) {
	case 'a':
		if (use_ns)
			n = sprintf(out, "(%010llu.%09llu) ", (unsigned long long)ts->tv_sec,
				    (unsigned long long)ts->tv_nsec);
		else
			n = sprintf(out, "(%010llu.%06llu) ", (unsigned long long)ts->tv_sec,
				    (unsigned long long)ts->tv_nsec / 1000);
		*shown_ns = ts->tv_sec * 1000000000LL + (use_ns ? ts->tv_nsec : ts->tv_nsec / 1000 * 1000);
		break;
	case 'A': {
		struct tm tm;
		char timestring[25];
		tm = *localtime(&ts->tv_sec);
		strftime(timestring, 24, "%Y-%m-%d %H:%M:%S", &tm);
		if (use_ns)
			n = sprintf(out, "(%s.%09llu) ", timestring, (unsigned long long)ts->tv_nsec);
		else
			n = sprintf(out, "(%s.%06llu) ", timestring,
				    (unsigned long long)ts->tv_nsec / 1000);
		*shown_ns = ts->tv_sec * 1000000000LL + (use_ns ? ts->tv_nsec : ts->tv_nsec / 1000 * 1000);
		break;
	}
	case 'd':
	case 'z': {
		struct timespec diff;
		if (last_ts->tv_sec == 0)
			*last_ts = *ts;
		diff.tv_sec = ts->tv_sec - last_ts->tv_sec;
		diff.tv_nsec = ts->tv_nsec - last_ts->tv_nsec;
		if (diff.tv_nsec < 0)
			diff.tv_sec--, diff.tv_nsec += 1000000000;
		if (diff.tv_sec < 0)
			diff.tv_sec = diff.tv_nsec = 0;
		if (use_ns)
			n = sprintf(out, "(%03llu.%09llu) ", (unsigned long long)diff.tv_sec,
				    (unsigned long long)diff.tv_nsec);
		else
			n = sprintf(out, "(%03llu.%06llu) ", (unsigned long long)diff.tv_sec,
				    (unsigned long long)diff.tv_nsec / 1000);
		long long shown = diff.tv_sec * 1000000000LL +
				  (use_ns ? diff.tv_nsec : diff.tv_nsec / 1000 * 1000);
		/* docs/formats.md#candump-relative-times: -t d accumulates the
		 * deltas, -t z is as written. */
		*shown_ns = (timestamp == 'd') ? *shown_ns + shown : shown;
		if (timestamp == 'd')
			*last_ts = *ts;
		break;
	}
	}
	return n;
}

int main(int argc, char **argv)
{
	if (argc != 4) {
		fprintf(stderr, "usage: %s MODE OUT.txt OUT.json\n", argv[0]);
		return 2;
	}
	const struct mode *m = NULL;
	for (size_t i = 0; i < sizeof(modes) / sizeof(modes[0]); i++)
		if (!strcmp(modes[i].name, argv[1]))
			m = &modes[i];
	if (!m) {
		fprintf(stderr, "unknown mode %s\n", argv[1]);
		return 2;
	}
	build();
	FILE *txt = fopen(argv[2], "w");
	FILE *js = fopen(argv[3], "w");
	if (!txt || !js)
		return 1;
	int view = m->view;
	struct timespec last_ts = { 0, 0 };
	long long shown_ns = 0;
	char buf[AFRSZ];
	fprintf(js, "{\"mode\": \"%s\", \"frames\": [\n", m->name);
	for (int i = 0; i < nframes; i++) {
		union cfu *cu = &frames[i];
		struct timespec ts;
		ts.tv_sec = base_sec + offsets_ns[i] / 1000000000LL;
		ts.tv_nsec = offsets_ns[i] % 1000000000LL;
		int idx = (ifname[i][3] == '1') ? 1 : 0;
		int alen;
		if (!is_fd[i] && (cu->cc.can_id & CAN_EFF_FLAG))
			view |= CANLIB_VIEW_INDENT_SFF; /* as candump.c does */
		alen = sprintf(buf, " %s", (m->color > 2) ? col_on[idx % MAXCOL] : "");
		alen += sprint_ts(buf + alen, m->timestamp, m->use_ns, &ts, &last_ts, &shown_ns);
		alen += sprintf(buf + alen, " %s%*s", (m->color && m->color < 3) ? col_on[idx % MAXCOL] : "",
				4, ifname[i]);
		if (m->extra) {
			alen += sprintf(buf + alen, (i % 4 == 1) ? "  TX" : "  RX");
			alen += sprintf(buf + alen, " %s", extra_fd_info[is_fd[i] ? cu->fd.flags & 3 : 0]);
		}
		alen += sprintf(buf + alen, "%s  ", (m->color == 1) ? col_off : "");
		alen += snprintf_long_canframe(buf + alen, sizeof(buf) - alen, cu, view);
		if ((view & CANLIB_VIEW_ERROR) && (cu->fd.can_id & CAN_ERR_FLAG)) {
			alen += sprintf(buf + alen, "\n\t");
			alen += snprintf_can_error_frame(buf + alen, sizeof(buf) - alen, &cu->fd, "\n\t");
		}
		fprintf(txt, "%s%s\n", buf, (m->color > 1) ? col_off : "");

		/* The truth: what the line says. */
		canid_t id = cu->fd.can_id;
		int err = !!(id & CAN_ERR_FLAG);
		int ext = err || !!(id & CAN_EFF_FLAG);
		int rtr = !!(id & CAN_RTR_FLAG);
		int len = cu->fd.len;
		fprintf(js, "  {\"iface\": \"%s\", \"id\": %u, \"extended\": %s, \"rtr\": %s, "
			"\"fd\": %s, \"brs\": %s, \"esi\": %s, \"error\": %s, \"dlc\": %d, \"data\": \"",
			ifname[i], err ? (id & CAN_ERR_MASK) : (id & (ext ? CAN_EFF_MASK : CAN_SFF_MASK)),
			ext ? "true" : "false", rtr ? "true" : "false", is_fd[i] ? "true" : "false",
			(m->extra && is_fd[i] && (cu->fd.flags & CANFD_BRS)) ? "true" : "false",
			(m->extra && is_fd[i] && (cu->fd.flags & CANFD_ESI)) ? "true" : "false",
			err ? "true" : "false", len);
		if (!rtr)
			for (int b = 0; b < len; b++)
				fprintf(js, "%02x", cu->fd.data[b]);
		fprintf(js, "\", \"direction\": %s, ", m->extra ? ((i % 4 == 1) ? "\"tx\"" : "\"rx\"") : "null");
		if (m->timestamp)
			fprintf(js, "\"ts\": \"%lld.%09lld\"}", shown_ns / 1000000000LL, shown_ns % 1000000000LL);
		else
			fprintf(js, "\"ts\": null}");
		fprintf(js, "%s\n", (i + 1 < nframes) ? "," : "");
	}
	fprintf(js, "]}\n");
	fclose(txt);
	fclose(js);
	return 0;
}
