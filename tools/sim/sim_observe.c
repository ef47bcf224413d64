/* SPDX-License-Identifier: Apache-2.0 */
/* modcp-sim — the line model's set-up: its settings, its members and the observers the
 * command line asks for (--capture FILE.pcap, --vcd FILE.vcd). */
#define _GNU_SOURCE
#include "sim.h"

bool open_observers(sim_t *s, const modcp_params_t *p0)
{
    bool ascii = p0->framing == MODCP_FRAMING_ASCII;
    sim_line_cfg_t cfg = {p0->data_bits, (uint8_t)p0->parity, p0->stop_bits, ascii, p0->baud,
                          modcp_params_char_us(p0),
                          ascii ? p0->ascii_timeout_ms * 1000u : modcp_params_t35_us(p0)};
    sim_line_init(&s->wire, &cfg, s->t0_us64);
    for (size_t i = 0; i < s->n; i++) {
        sim_line_member(&s->wire, i, s->m[i].name, s->m[i].conf->params.slave_addr);
    }
    for (size_t i = 0; i < s->n_ext; i++) {
        sim_line_member(&s->wire, s->n + i, s->ext_name[i], 0);
    }
    char err[160];
    if (s->capture_path != NULL) {
        s->capture = sim_capture_open(&s->wire, s->capture_path, err, sizeof err);
        if (s->capture == NULL) {
            fprintf(stderr, "modcp-sim: --capture %s: %s\n", s->capture_path, err);
            return false;
        }
        (void)sim_line_observe(&s->wire, sim_capture_observer(s->capture));
    }
    if (s->vcd_path != NULL) {
        s->vcd = sim_vcd_open(&s->wire, s->vcd_path, err, sizeof err);
        if (s->vcd == NULL) {
            fprintf(stderr, "modcp-sim: --vcd %s: %s\n", s->vcd_path, err);
            return false;
        }
        (void)sim_line_observe(&s->wire, sim_vcd_observer(s->vcd));
    }
    return true;
}

void close_observers(sim_t *s)
{
    sim_line_close(&s->wire);
    if (s->capture != NULL) {
        uint32_t n = sim_capture_close(s->capture);
        s->capture = NULL;
        printf_line(s, "modcp-sim: capture %s: %u records", s->capture_path, (unsigned)n);
    }
    if (s->vcd != NULL) {
        sim_vcd_close(s->vcd);
        s->vcd = NULL;
        printf_line(s, "modcp-sim: waveform %s written", s->vcd_path);
    }
}
