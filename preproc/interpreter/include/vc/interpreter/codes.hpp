// G and M codes by name, as LinuxCNC's rs274ngc stores them (interp_internal.hh): ten times
// the code, so that G59.1 is 591 and M3 is 30. Ints, not an enum: the interpreter reads a
// code's number back (G72 and G72.1 are code / 10 == 72, G71.2's pass is code % 10) and
// checks ranges (G81 .. G89 are the drilling cycles).
#pragma once

namespace vc::interpreter {

// ---- G codes ------------------------------------------------------------------------------
constexpr int G_0 = 0, G_1 = 10, G_2 = 20, G_3 = 30, G_4 = 40;
constexpr int G_5 = 50, G_5_1 = 51, G_5_2 = 52, G_5_3 = 53;  // splines: cubic, quadratic, NURBS
constexpr int G_7 = 70, G_8 = 80;                            // lathe diameter / radius mode
constexpr int G_10 = 100;
constexpr int G_17_1 = 171, G_18_1 = 181, G_19_1 = 191;  // refused
constexpr int G_17 = 170, G_18 = 180, G_19 = 190;        // planes XY, XZ, YZ
constexpr int G_20 = 200, G_21 = 210;                    // inches, mm
constexpr int G_28 = 280, G_28_1 = 281, G_30 = 300, G_30_1 = 301;
constexpr int G_33 = 330, G_33_1 = 331, G_38_2 = 382, G_38_3 = 383, G_38_4 = 384,
              G_38_5 = 385;                                                    // refused: spindle-synchronised, probing
constexpr int G_40 = 400, G_41 = 410, G_41_1 = 411, G_42 = 420, G_42_1 = 421;  // cutter compensation
constexpr int G_43 = 430, G_43_1 = 431, G_43_2 = 432, G_49 = 490;              // tool length offset
constexpr int G_52 = 520, G_53 = 530;
constexpr int G_54 = 540, G_55 = 550, G_56 = 560, G_57 = 570, G_58 = 580, G_59 = 590, G_59_1 = 591, G_59_2 = 592,
              G_59_3 = 593;
constexpr int G_61 = 610, G_61_1 = 611, G_64 = 640;                                                        // path modes
constexpr int G_70 = 700, G_71 = 710, G_71_1 = 711, G_71_2 = 712, G_72 = 720, G_72_1 = 721, G_72_2 = 722;  // lathe
constexpr int G_73 = 730, G_74 = 740, G_76 = 760;
constexpr int G_80 = 800, G_81 = 810, G_82 = 820, G_83 = 830, G_84 = 840, G_85 = 850, G_86 = 860, G_87 = 870,
              G_88 = 880, G_89 = 890;
constexpr int G_90 = 900, G_90_1 = 901, G_91 = 910, G_91_1 = 911;  // distance modes, and of arcs' centres
constexpr int G_92 = 920, G_92_1 = 921, G_92_2 = 922, G_92_3 = 923;
constexpr int G_93 = 930, G_94 = 940, G_95 = 950;  // feed modes: inverse time, per minute, per revolution
constexpr int G_96 = 960, G_97 = 970;              // spindle: constant surface speed, rpm
constexpr int G_98 = 980, G_99 = 990;              // canned cycles retract to the start Z, to R

// ---- M codes ------------------------------------------------------------------------------
constexpr int M_0 = 0, M_1 = 10, M_2 = 20, M_30 = 300, M_60 = 600;  // stops and program ends
constexpr int M_3 = 30, M_4 = 40, M_5 = 50;                         // spindle
constexpr int M_6 = 60, M_61 = 610;                                 // tool change
constexpr int M_7 = 70, M_8 = 80, M_9 = 90;                         // coolant
constexpr int M_19 = 190;
constexpr int M_48 = 480, M_49 = 490, M_50 = 500, M_51 = 510, M_52 = 520, M_53 = 530;              // overrides
constexpr int M_62 = 620, M_63 = 630, M_64 = 640, M_65 = 650, M_66 = 660, M_67 = 670, M_68 = 680;  // I/O
constexpr int M_70 = 700, M_71 = 710, M_72 = 720, M_73 = 730;  // modal state: save, invalidate, restore, auto

}  // namespace vc::interpreter
