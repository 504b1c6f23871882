set(CUTROUTE_COST_SOURCES estimate.cpp machine_profile.cpp motion_model.cpp speed_table.cpp)
