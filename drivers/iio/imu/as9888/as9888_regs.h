/* SPDX-License-Identifier: GPL-2.0 */
/*
 * AS9888 register map and timing (datasheet sections 2, 3 and 5).
 */
#ifndef AS9888_REGS_H
#define AS9888_REGS_H

#include <linux/bits.h>

#define AS9888_REG_WIA			0x00
#define AS9888_WIA_VAL			0x48

#define AS9888_REG_INT1EN		0x02
#define AS9888_REG_INT2EN		0x03
#define AS9888_INTEN_DR_MSK		BIT(0)

#define AS9888_REG_INT1ST		0x04
#define AS9888_REG_INT2ST		0x05
#define AS9888_INTST_DR_MSK		BIT(0)

#define AS9888_REG_SLCT1		0x06
#define AS9888_REG_SLCT2		0x07
#define AS9888_SLCT2_MEN_MSK		BIT(2)
#define AS9888_SLCT2_ALPF_MSK		BIT(3)

#define AS9888_REG_MS			0x08
#define AS9888_MS_POWER_DOWN		0x00
#define AS9888_MS_SINGLE		0x01
#define AS9888_MS_EEPROM		0x04
#define AS9888_MS_SELF_TEST		0x08

/* One burst of 0x10..0x1f is a whole sample */
#define AS9888_REG_ST1			0x10
#define AS9888_ST1_DRDY_MSK		BIT(0)
#define AS9888_ST1_DOR_MSK		BIT(1)
#define AS9888_REG_HXL			0x11
#define AS9888_REG_TMPS			0x17
#define AS9888_REG_EMPT			0x18
#define AS9888_REG_A1XL			0x19
#define AS9888_REG_ST2			0x1f
#define AS9888_ST2_HST_MSK		BIT(1)
#define AS9888_ST2_HOFL_MSK		BIT(3)
#define AS9888_SAMPLE_LEN		(AS9888_REG_ST2 - AS9888_REG_ST1 + 1)

/* Trim registers, writable in power-down only */
#define AS9888_REG_REF1			0x30
#define AS9888_REG_REF2			0x31
#define AS9888_REG_REF3			0x32
#define AS9888_REG_OSC			0x33
#define AS9888_REG_AXGA			0x34
#define AS9888_REG_AGA(axis)		(AS9888_REG_AXGA + (axis))
#define AS9888_REG_AXDA			0x37
#define AS9888_REG_ADA(axis)		(AS9888_REG_AXDA + (axis))
#define AS9888_REG_AZDA			0x39
#define AS9888_TRIM_LEN			(AS9888_REG_AZDA - AS9888_REG_REF1 + 1)
/* REF3: bits 7..3 fixed, the trim field below from EREF3 */
#define AS9888_REF3_FIXED		0x18
/* AxGA: the DAC polarity and the gain */
#define AS9888_GA_POLARITY_MSK		BIT(6)
#define AS9888_GA_GAIN_MSK		GENMASK(5, 0)
/*
 * AxDA, the offset DAC: 0..67 is the linear code 0..-67, 0x80..0xc3 the
 * linear code 0..67 (before the polarity of AxGA)
 */
#define AS9888_DAC_NEG_MAX		67
#define AS9888_DAC_ZERO			0x80	/* reset value: linear code 0 */
#define AS9888_DAC_LIN_MAX		AS9888_DAC_NEG_MAX	/* either side of 0 */
#define AS9888_DAC_POS_MAX		(AS9888_DAC_ZERO + AS9888_DAC_LIN_MAX)

/* EEPROM window, readable in EEPROM access mode after t_EEP */
#define AS9888_REG_EEPROM		0x40
#define AS9888_REG_EEPROM_END		0x54
/* Bit fields of the EEPROM bytes */
#define AS9888_EREF3_TRT_MSK		GENMASK(7, 3)
#define AS9888_EREF3_TRIM_MSK		GENMASK(2, 0)
#define AS9888_EAGA_DT_SIGN_MSK		BIT(7)
#define AS9888_EAGA_REG_MSK		GENMASK(6, 0)
#define AS9888_EAGTD_KSTE_MSK		GENMASK(7, 5)
#define AS9888_EAGTD_DETAIL_MSK		GENMASK(4, 0)

/* Timing, microseconds */
#define AS9888_T_RSTL_US		5
#define AS9888_T_BOOT_US		100
#define AS9888_T_EEP_US			300
#define AS9888_T_PD_US			100
#define AS9888_T_ACC_US			1200
#define AS9888_T_ACC_LPF_US		4800
#define AS9888_T_MAG_US			7300

#endif /* AS9888_REGS_H */
