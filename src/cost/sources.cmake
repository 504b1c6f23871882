set(CUTROUTE_COST_SOURCES estimate.cpp machine_profile.cpp speed_table.cpp)
